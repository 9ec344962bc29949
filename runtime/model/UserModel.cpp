#include "UserModel.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace cbtl::model {

using nlohmann::json;

GeneratorState::GeneratorState(const ir::Generator& spec, const std::shared_ptr<const textpref::TextBackend>& textBackend)
    : spec_(&spec) {
  for (const auto& f : spec.factors) prior_.push_back(Factor::fromSpec(f, spec.fallback, textBackend));
}

const std::vector<Factor>& GeneratorState::factors(const std::string& key) const {
  auto it = byKey_.find(key);
  return it == byKey_.end() ? prior_ : it->second;
}

std::vector<Factor>& GeneratorState::mutableFactors(const std::string& key) {
  ++version_;
  auto it = byKey_.find(key);
  if (it == byKey_.end()) it = byKey_.emplace(key, prior_).first;
  return it->second;
}

UserModel::UserModel(const ir::ConstraintGraph& graph, std::shared_ptr<const textpref::TextBackend> textBackend)
    : domain_(graph.domain) {
  if (!textBackend) textBackend = defaultTextBackend();
  for (const auto& g : graph.generators) generators_.emplace_back(g, textBackend);
}

void UserModel::reset() {
  for (auto& g : generators_) {
    g.reset();
    g.touch();
  }
}

std::size_t UserModel::dataCount() const {
  std::size_t n = 0;
  for (const auto& g : generators_) {
    for (const auto& [key, factors] : g.keys()) {
      for (const auto& f : factors) {
        if (const auto* i = std::get_if<IntervalModel>(&f.model())) n += i->data().size();
        else if (const auto* t = std::get_if<ThresholdModel>(&f.model())) n += t->data().size();
        else if (const auto* tb = std::get_if<TableModel>(&f.model())) n += tb->entries().size();
        else if (const auto* tx = std::get_if<TextFactor>(&f.model())) n += tx->historySize();
      }
    }
  }
  return n;
}

std::string UserModel::toJson() const {
  json gens = json::object();
  for (const auto& g : generators_) {
    json keys = json::object();
    for (const auto& [key, factors] : g.keys()) {
      json fs = json::object();
      for (const auto& f : factors) {
        json j;
        if (const auto* i = std::get_if<IntervalModel>(&f.model())) {
          j = {{"kind", "interval"}, {"lo", i->lo()}, {"hi", i->hi()}, {"data", i->data()},
               {"trapezoid", {i->x1(), i->x2(), i->x3(), i->x4()}}};
        } else if (const auto* t = std::get_if<ThresholdModel>(&f.model())) {
          j = {{"kind", "threshold"}, {"lo", t->lo()}, {"hi", t->hi()}, {"data", t->data()},
               {"direction", t->direction() == ThresholdModel::Direction::Above ? "above" : "below"}};
        } else if (const auto* tb = std::get_if<TableModel>(&f.model())) {
          j = {{"kind", "table"}, {"entries", tb->entries()}};
        } else if (const auto* tx = std::get_if<TextFactor>(&f.model())) {
          j = {{"kind", "text"}, {"backend", tx->backendId()}, {"state", tx->saveState()}};
        }
        fs[f.label()] = j;
      }
      keys[key] = fs;
    }
    gens[g.spec().name] = keys;
  }
  json root = {{"format", "cbtl-profile"}, {"version", 1}, {"domain", domain_}, {"generators", gens}};
  return root.dump(2) + "\n";
}

void UserModel::fromJson(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw ProfileError(fmt::format("{}: not valid JSON (byte {}): {}", source, e.byte, e.what()));
  }
  auto fail = [&](const std::string& path, const std::string& what) {
    throw ProfileError(fmt::format("{}: {}: {}", source, path, what));
  };
  if (!root.is_object() || root.value("format", "") != "cbtl-profile") fail("format", "expected \"cbtl-profile\"");
  if (!root.contains("version") || !root["version"].is_number_integer() || root["version"].get<int>() != 1) {
    fail("version", "expected 1");
  }
  if (root.value("domain", "") != domain_) {
    fail("domain", fmt::format("profile is for domain '{}', this program is '{}'", root.value("domain", ""), domain_));
  }
  if (!root.contains("generators") || !root["generators"].is_object()) fail("generators", "expected an object");
  // Parse into a copy first, so a bad profile leaves the current model untouched.
  std::vector<GeneratorState> parsed = generators_;
  for (auto& g : parsed) g.reset();
  for (const auto& [name, keys] : root["generators"].items()) {
    GeneratorState* state = nullptr;
    for (auto& g : parsed) {
      if (g.spec().name == name) state = &g;
    }
    const std::string gpath = "generators." + name;
    if (state == nullptr) fail(gpath, "no such generator in this program");
    if (!keys.is_object()) fail(gpath, "expected an object of model keys");
    for (const auto& [key, factors] : keys.items()) {
      const std::string kpath = gpath + "[\"" + key + "\"]";
      if (!factors.is_object()) fail(kpath, "expected an object of factors");
      auto& fs = state->mutableFactors(key);
      for (auto& f : fs) {
        const std::string fpath = kpath + "." + f.label();
        if (!factors.contains(f.label())) fail(fpath, "missing factor");
        const json& j = factors[f.label()];
        if (!j.is_object()) fail(fpath, "expected an object");
        if (auto* textFactor = std::get_if<TextFactor>(&f.model())) {
          if (!j.contains("kind") || j["kind"] != "text") fail(fpath + ".kind", "expected \"text\" (the program declares a text model)");
          if (!j.contains("backend") || !j["backend"].is_string()) fail(fpath + ".backend", "expected the text backend's id");
          const std::string backend = j["backend"].get<std::string>();
          if (backend != textFactor->backendId()) {
            fail(fpath + ".backend", fmt::format("saved by the '{}' text backend, this run uses '{}'", backend, textFactor->backendId()));
          }
          if (!j.contains("state") || !j["state"].is_object()) fail(fpath + ".state", "expected the text model's state object");
          if (const textpref::Status s = textFactor->loadState(j["state"]); !s.ok()) fail(fpath + ".state", s.error().message);
          continue;
        }
        if (f.isTable()) {
          if (!j.contains("entries") || !j["entries"].is_object()) fail(fpath + ".entries", "expected an object");
          for (const auto& [k, v] : j["entries"].items()) {
            if (!v.is_boolean()) fail(fpath + ".entries." + k, "expected true or false");
            f.observe(k, v.get<bool>());
          }
          continue;
        }
        if (!j.contains("data") || !j["data"].is_array()) fail(fpath + ".data", "expected an array of [x, label]");
        std::size_t i = 0;
        for (const auto& d : j["data"]) {
          if (!d.is_array() || d.size() != 2 || !d[0].is_number() || !d[1].is_boolean()) {
            fail(fmt::format("{}.data[{}]", fpath, i), "expected [number, true|false]");
          }
          f.observe(d[0].get<double>(), d[1].get<bool>());
          ++i;
        }
      }
    }
  }
  for (auto& g : parsed) g.touch();
  generators_ = std::move(parsed);
  for (auto& g : generators_) g.touch();
}

void UserModel::save(const std::string& path) const {
  // A temporary name of its own (pid and a per-process counter), so two writers of one path never share it.
  static std::atomic<unsigned> counter{0};
  const std::string tmp = fmt::format("{}.tmp.{}.{}", path, static_cast<long>(getpid()), counter++);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw ProfileError(fmt::format("{}: cannot write", tmp));
    out << toJson();
    out.close();  // flushes: a full disk shows here
    if (!out) {
      std::remove(tmp.c_str());
      throw ProfileError(fmt::format("{}: write failed (disk full?)", tmp));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw ProfileError(fmt::format("{}: cannot replace", path));
  }
}

void UserModel::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProfileError(fmt::format("{}: cannot read the profile", path));
  std::stringstream ss;
  ss << in.rdbuf();
  fromJson(ss.str(), path);
}

}  // namespace cbtl::model
