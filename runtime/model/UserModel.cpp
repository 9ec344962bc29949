#include "runtime/model/UserModel.h"

#include "ir/OpNames.h"
#include "support/InputFile.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace cbtl::model {

using nlohmann::json;

GeneratorState::GeneratorState(const ir::Generator& spec,
                               const std::shared_ptr<const textpref::TextBackend>& textBackend)
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
    : domain_(graph.domain), graph_(&graph) {
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
      for (const auto& f : factors) n += f.evidenceCount();
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
          j = {{"kind", "interval"},
               {"lo", i->lo()},
               {"hi", i->hi()},
               {"data", i->data()},
               {"trapezoid", {i->x1(), i->x2(), i->x3(), i->x4()}}};
        } else if (const auto* t = std::get_if<ThresholdModel>(&f.model())) {
          j = {{"kind", "threshold"},
               {"lo", t->lo()},
               {"hi", t->hi()},
               {"data", t->data()},
               {"direction", t->direction() == ThresholdModel::Direction::Above ? "above" : "below"}};
        } else if (const auto* tb = std::get_if<TableModel>(&f.model())) {
          j = {{"kind", "table"}, {"entries", tb->entries()}};
        } else if (const auto* tx = std::get_if<TextFactor>(&f.model())) {
          // theta is stored for people reading the profile; loading restores it from the state.
          j = {{"kind", "text"},
               {"backend", tx->backendId()},
               {"theta", tx->model().thetaText()},
               {"state", tx->saveState()}};
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

namespace {

[[noreturn]] void failAt(const std::string& source, const std::string& path, const std::string& what) {
  throw ProfileError(fmt::format("{}: {}: {}", source, path, what));
}

// Loads the saved data of one factor whose kind the program declares as `spec.kind`.
void loadFactor(Factor& f, const ir::ModelFactor& spec, const json& j, const std::string& source,
                const std::string& fpath) {
  auto fail = [&](const std::string& path, const std::string& what) { failAt(source, path, what); };
  if (!j.is_object()) fail(fpath, "expected an object");
  const std::string_view kind = ir::name(spec.kind);
  if (!j.contains("kind") || !j["kind"].is_string() || j["kind"].get<std::string>() != kind) {
    const std::string saved = j.contains("kind") ? j["kind"].dump() : std::string("nothing");
    fail(fpath + ".kind",
         fmt::format("expected \"{}\" (the program declares a {} model), the profile has {}", kind, kind, saved));
  }
  if (auto* textFactor = std::get_if<TextFactor>(&f.model())) {
    if (!j.contains("backend") || !j["backend"].is_string()) fail(fpath + ".backend", "expected the text backend's id");
    const std::string backend = j["backend"].get<std::string>();
    if (backend != textFactor->backendId()) {
      fail(fpath + ".backend",
           fmt::format("saved by the '{}' text backend, this run uses '{}'", backend, textFactor->backendId()));
    }
    if (!j.contains("state") || !j["state"].is_object())
      fail(fpath + ".state", "expected the text model's state object");
    if (const textpref::Status st = textFactor->loadState(j["state"]); !st.ok())
      fail(fpath + ".state", st.error().message);
    return;
  }
  if (f.isTable()) {
    if (!j.contains("entries") || !j["entries"].is_object()) fail(fpath + ".entries", "expected an object");
    for (const auto& [k, v] : j["entries"].items()) {
      if (!v.is_boolean()) fail(fpath + ".entries." + k, "expected true or false");
      f.observe(k, v.get<bool>());
    }
    return;
  }
  if (!j.contains("data") || !j["data"].is_array()) fail(fpath + ".data", "expected an array of [x, label]");
  const json& data = j["data"];
  std::vector<std::pair<double, bool>> points;
  points.reserve(data.size());
  for (std::size_t i = 0; i < data.size(); ++i) {
    const json& d = data[i];
    if (!d.is_array() || d.size() != 2 || !d[0].is_number() || !d[1].is_boolean()) {
      fail(fmt::format("{}.data[{}]", fpath, i), "expected [number, true|false]");
    }
    points.emplace_back(d[0].get<double>(), d[1].get<bool>());
  }
  f.observeAll(points);  // one fit for all points: linear in the profile's size
}

// Which enum a per-key part of kind "enum" ranges over, or null.
const ir::Enum* findEnum(const ir::ConstraintGraph& graph, const std::string& name) {
  for (const auto& e : graph.enums) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

// A model key is the generator's `per` parts joined by '|' (Personalization.cpp, Learner.cpp): as many parts as
// `per` names (more only when a free-text part may itself hold '|'), a bool part true|false, an int part an
// integer, an enum part one of the enum's members.
void checkKey(const ir::ConstraintGraph& graph, const ir::Generator& g, const std::string& key,
              const std::string& source, const std::string& kpath) {
  std::vector<std::string> parts;
  if (!g.perKeys.empty()) {
    std::size_t from = 0;
    for (std::size_t bar = key.find('|'); bar != std::string::npos; bar = key.find('|', from)) {
      parts.push_back(key.substr(from, bar - from));
      from = bar + 1;
    }
    parts.push_back(key.substr(from));
  } else if (!key.empty()) {
    failAt(source, kpath, fmt::format("generator '{}' has no 'per' keys, so its only model key is \"\"", g.name));
  }
  bool freeText = false;
  std::vector<const ir::TypeDesc*> types;
  std::vector<std::string> names;
  for (const auto& perKey : g.perKeys) {
    names.push_back(perKey.name);
    const ir::TypeDesc* type = perKey.expr ? &perKey.expr->type : nullptr;
    for (const auto& p : g.params) {
      if (!perKey.expr && p.name == perKey.name) type = &p.type;
    }
    freeText = freeText || type == nullptr || type->kind == ir::TypeKind::Text;
    types.push_back(type);
  }
  if (parts.size() < g.perKeys.size() || (parts.size() > g.perKeys.size() && !freeText)) {
    failAt(source, kpath,
           fmt::format("expected {} '|'-separated part{} (per {}), found {}", g.perKeys.size(),
                       g.perKeys.size() == 1 ? "" : "s", fmt::join(names, ", "), parts.size()));
  }
  if (parts.size() != g.perKeys.size()) return;  // a free-text part holds a '|': the parts cannot be told apart
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (types[i] == nullptr) continue;  // a capture: any text
    const ir::TypeKind kind = types[i]->kind;
    const std::string& part = parts[i];
    std::string problem;
    if (kind == ir::TypeKind::Bool && part != "true" && part != "false") problem = "true or false";
    if (kind == ir::TypeKind::Int && (part.empty() || part.find_first_not_of("-0123456789") != std::string::npos))
      problem = "an integer";
    if (kind == ir::TypeKind::Enum) {
      const ir::Enum* e = findEnum(graph, types[i]->spelling);
      if (e != nullptr && std::find(e->members.begin(), e->members.end(), part) == e->members.end())
        problem = fmt::format("a member of {} ({})", e->name, fmt::join(e->members, ", "));
    }
    if (!problem.empty())
      failAt(source, kpath, fmt::format("part {} ('{}', per {}) should be {}", i + 1, part, names[i], problem));
  }
}

}  // namespace

void UserModel::fromJson(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw ProfileError(fmt::format("{}: not valid JSON (byte {}): {}", source, e.byte, e.what()));
  }
  auto fail = [&](const std::string& path, const std::string& what) { failAt(source, path, what); };
  if (!root.is_object() || root.value("format", "") != "cbtl-profile") fail("format", "expected \"cbtl-profile\"");
  if (!root.contains("version") || !root["version"].is_number_integer() || root["version"].get<int>() != 1) {
    fail("version", "expected 1");
  }
  if (!root.contains("domain") || !root["domain"].is_string() || root["domain"].get<std::string>() != domain_) {
    fail("domain", fmt::format("profile is for domain {}, this program is '{}'",
                               root.contains("domain") ? root["domain"].dump() : "(none)", domain_));
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
      checkKey(*graph_, state->spec(), key, source, kpath);
      if (!factors.is_object()) fail(kpath, "expected an object of factors");
      auto& fs = state->mutableFactors(key);
      for (const auto& entry : factors.items()) {
        const std::string& label = entry.key();  // not a structured binding: clang 14 cannot capture those
        const bool known = std::any_of(fs.begin(), fs.end(), [&](const Factor& f) { return f.label() == label; });
        if (!known) fail(kpath + "." + label, "no such factor in this generator");
      }
      for (std::size_t k = 0; k < fs.size(); ++k) {
        const std::string fpath = kpath + "." + fs[k].label();
        if (!factors.contains(fs[k].label())) fail(fpath, "missing factor");
        loadFactor(fs[k], state->spec().factors[k], factors[fs[k].label()], source, fpath);
      }
    }
  }
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
  std::string text;
  try {
    text = support::readInputFile(path, support::kMaxDataBytes, "profile");
  } catch (const support::InputFileError& e) {
    throw ProfileError(e.what());
  }
  fromJson(text, path);
}

}  // namespace cbtl::model
