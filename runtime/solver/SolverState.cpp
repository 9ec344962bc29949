// SolverState.cpp — Solver::saveState / restoreState (declared at the end of Solver.h), for checkpoints.
//
// State document: {"rng": "<std::mt19937_64 text>", "memory_size": N,
//                   "memory": [{"identity": "<uint64 as decimal text>", "width": W, "capacity": C, "count": K,
//                               "head": H, "last": L, "ring": "<16 hex digits per double, the bits of each>"}]}
// Identities are 64-bit and written as text (JSON numbers lose precision past 2^53 in other readers).
#include "runtime/solver/Solver.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <stdexcept>

namespace cbtl::solver {

namespace {

std::string doublesToHex(const std::vector<double>& values) {
  std::string out;
  out.reserve(values.size() * 16);
  for (double v : values) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    out += fmt::format("{:016x}", bits);
  }
  return out;
}

std::vector<double> hexToDoubles(const std::string& text) {
  if (text.size() % 16 != 0) throw std::runtime_error("solver state: a memory ring is not a whole number of doubles");
  std::vector<double> out(text.size() / 16);
  for (std::size_t i = 0; i < out.size(); ++i) {
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < 16; ++k) {
      const char c = text[i * 16 + k];
      int d;
      if (c >= '0' && c <= '9')
        d = c - '0';
      else if (c >= 'a' && c <= 'f')
        d = c - 'a' + 10;
      else
        throw std::runtime_error("solver state: a memory ring holds a character that is not a hex digit");
      bits = (bits << 4) | static_cast<std::uint64_t>(d);
    }
    std::memcpy(&out[i], &bits, sizeof bits);
  }
  return out;
}

}  // namespace

nlohmann::json Solver::saveState() const {
  nlohmann::json memory = nlohmann::json::array();
  for (const auto& [identity, m] : memory_) {
    memory.push_back({{"identity", std::to_string(identity)},
                      {"width", m.width},
                      {"capacity", m.capacity},
                      {"count", m.count},
                      {"head", m.head},
                      {"last", m.last},
                      {"ring", doublesToHex(m.ring)}});
  }
  return {{"rng", rng_.saveState()}, {"memory_size", options_.memorySize}, {"memory", memory}};
}

void Solver::restoreState(const nlohmann::json& state) {
  try {
    if (state.at("memory_size").get<std::size_t>() != options_.memorySize) {
      throw std::runtime_error("solver state: saved with another memory size");
    }
    rt::Rng rng;
    if (!rng.restoreState(state.at("rng").get<std::string>()))
      throw std::runtime_error("solver state: the RNG state is malformed");
    std::map<std::uint64_t, Memory> memory;
    for (const auto& j : state.at("memory")) {
      Memory m;
      m.width = j.at("width").get<std::size_t>();
      m.capacity = j.at("capacity").get<std::size_t>();
      m.count = j.at("count").get<std::size_t>();
      m.head = j.at("head").get<std::size_t>();
      m.last = j.at("last").get<std::size_t>();
      m.ring = hexToDoubles(j.at("ring").get<std::string>());
      if (m.ring.size() != m.width * m.capacity || m.count > m.capacity ||
          (m.capacity > 0 && (m.head >= m.capacity || m.last >= m.capacity))) {
        throw std::runtime_error("solver state: a memory ring does not fit its sizes");
      }
      memory[std::stoull(j.at("identity").get<std::string>())] = std::move(m);
    }
    rng_ = rng;
    memory_ = std::move(memory);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("solver state: ") + e.what());
  } catch (const std::logic_error& e) {  // std::stoull
    throw std::runtime_error(std::string("solver state: a memory identity is not a number: ") + e.what());
  }
}

}  // namespace cbtl::solver
