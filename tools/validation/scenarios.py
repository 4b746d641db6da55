"""Which .sumocfg files a validation run covers: the ../shared scenario folders and osmWebWizard-style folders."""
import glob
import os

RUN_CFG = "run.sumocfg"


def folder_config(folder):
    """The cfgs to run in one scenario folder: its run.sumocfg where there is one (the folder's other cfgs are
    then kept for reference only, as dlr_badhersfeld_bus/present.sumocfg), else its .sumocfg files (normally
    a single one). Sorted; empty when the folder has none."""
    preferred = os.path.join(folder, RUN_CFG)
    if os.path.isfile(preferred):
        return [preferred]
    return sorted(glob.glob(os.path.join(folder, "*.sumocfg")))


def shared_configs(scenarios_dir):
    """The cfgs of every scenario folder directly under scenarios_dir (folders without a cfg are skipped)."""
    configs = []
    for name in sorted(os.listdir(scenarios_dir)):
        folder = os.path.join(scenarios_dir, name)
        if os.path.isdir(folder) and not name.startswith("."):
            configs += folder_config(folder)
    return configs


def wizard_configs(extra_dir):
    """Every DIR/*/osm.sumocfg (the layout tools/make_wizard_scenarios.py and osmWebWizard write)."""
    return sorted(glob.glob(os.path.join(extra_dir, "*", "osm.sumocfg")))


def model_list(model):
    """--model: 'both' means SUMO's default Krauss and then IDM; anything else is the one model named."""
    return ["Krauss", "IDM"] if model.lower() == "both" else [model]
