#include "transport/transport.hpp"

#include <cstdio>

namespace lpsim {

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

std::vector<Bytes> Transport::allgather(const Bytes& mine, const std::string& what) {
  std::vector<int> others;
  for (int r = 0; r < size(); ++r)
    if (r != rank()) others.push_back(r);
  const std::vector<Bytes> got = exchange(others, std::vector<Bytes>(others.size(), mine), others, what);
  std::vector<Bytes> all(static_cast<size_t>(size()));
  all[static_cast<size_t>(rank())] = mine;
  for (size_t i = 0; i < others.size(); ++i) all[static_cast<size_t>(others[i])] = got[i];
  return all;
}

void Transport::check_same_build(const std::string& build_id) {
  const std::vector<Bytes> ids = allgather(Bytes(build_id.begin(), build_id.end()), "build check");
  for (int r = 0; r < size(); ++r) {
    const std::string other(ids[static_cast<size_t>(r)].begin(), ids[static_cast<size_t>(r)].end());
    if (other != build_id)
      throw TransportError("rank " + std::to_string(r) + " runs build '" + other + "', rank " +
                           std::to_string(rank()) + " build '" + build_id +
                           "': every rank must run the same build");
  }
}

}  // namespace lpsim
