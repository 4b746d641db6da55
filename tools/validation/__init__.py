"""Validation of LPSim against SUMO: run both on one scenario, parse their outputs, compare, report."""
