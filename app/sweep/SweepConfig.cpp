#include "app/sweep/SweepConfig.h"

#include "support/InputFile.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace cbtl::sweep {

namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

// Errors name the file and the JSON pointer of the offending value.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw SweepError(fmt::format("{}: {}: {}", file_, where.empty() ? "/" : where, what));
  }

  void onlyKeys(const json& object, const std::string& where, const std::set<std::string>& allowed) const {
    if (!object.is_object()) fail(where, "must be an object");
    for (const auto& [key, value] : object.items())
      if (!allowed.count(key))
        fail(where + "/" + key, fmt::format("unknown key (known here: {})", fmt::join(allowed, ", ")));
  }
  std::string text(const json& v, const std::string& where) const {
    if (!v.is_string()) fail(where, "must be a string");
    return v.get<std::string>();
  }
  std::vector<std::string> texts(const json& v, const std::string& where) const {
    if (!v.is_array()) fail(where, "must be an array of strings");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(text(v[i], fmt::format("{}/{}", where, i)));
    return out;
  }
  double number(const json& v, const std::string& where) const {
    if (!v.is_number()) fail(where, "must be a number");
    return v.get<double>();
  }
  int count(const json& v, const std::string& where, int lo) const {
    if (!v.is_number_integer() || v.get<std::int64_t>() < lo || v.get<std::int64_t>() > 1000000)
      fail(where, fmt::format("must be a whole number from {} to 1000000", lo));
    return static_cast<int>(v.get<std::int64_t>());
  }

 private:
  std::string file_;
};

bool safeName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  });
}

// The options the sweep sets for every trial, or that would break its bookkeeping.
const std::set<std::string>& reservedOptions() {
  static const std::set<std::string> reserved = {"approach", "seed", "out",  "force", "resume",
                                                 "quiet",    "q",    "jobs", "file",  "help"};
  return reserved;
}

void readOptions(const Reader& r, const json& v, const std::string& where, OptionList& out) {
  if (!v.is_object()) r.fail(where, "must be an object of cbtl run options");
  for (const auto& [name, value] : v.items()) {
    const std::string at = where + "/" + name;
    if (reservedOptions().count(name)) r.fail(at, "the sweep sets this option itself");
    if (name.empty() || name[0] == '-') r.fail(at, "an option's name has no dashes (\"steps\", not \"--steps\")");
    if (!value.is_number() && !value.is_string() && !value.is_boolean())
      r.fail(at, "must be a number, a string or true/false");
    out.emplace_back(name, value);
  }
}

ExperimentSpec readExperiment(const Reader& r, const json& v, const std::string& where, const fs::path& base,
                              const OptionList& defaults) {
  r.onlyKeys(v, where, {"name", "program", "approaches", "seeds", "options", "grid", "columns"});
  ExperimentSpec e;
  e.where = where;
  if (!v.contains("name")) r.fail(where, "an experiment needs a \"name\"");
  e.name = r.text(v["name"], where + "/name");
  if (!safeName(e.name)) r.fail(where + "/name", "use letters, digits, '.', '_' and '-' (it names a folder)");
  if (!v.contains("program")) r.fail(where, "an experiment needs a \"program\" (a .cbtl file or an emitted graph)");
  e.program = fs::absolute(base / r.text(v["program"], where + "/program")).lexically_normal().string();
  if (!fs::is_regular_file(e.program)) r.fail(where + "/program", "no such file: " + e.program);
  e.approaches = v.contains("approaches") ? r.texts(v["approaches"], where + "/approaches")
                                          : std::vector<std::string>{"cbtl", "no-personalization"};
  if (e.approaches.empty()) r.fail(where + "/approaches", "needs at least one approach");
  const std::string seeds = v.contains("seeds")
                                ? (v["seeds"].is_number_unsigned() ? std::to_string(v["seeds"].get<std::uint64_t>())
                                                                   : r.text(v["seeds"], where + "/seeds"))
                                : "0..9";
  if (!parseSeedList(seeds, e.seeds))
    r.fail(where + "/seeds", fmt::format("'{}': use \"LO..HI\" or a comma-separated list of seeds", seeds));
  e.options = defaults;
  if (v.contains("options")) readOptions(r, v["options"], where + "/options", e.options);
  if (v.contains("columns")) {
    if (!v["columns"].is_array()) r.fail(where + "/columns", "must be an array of training steps");
    for (std::size_t i = 0; i < v["columns"].size(); ++i)
      e.columns.push_back(r.count(v["columns"][i], fmt::format("{}/columns/{}", where, i), 0));
  }
  if (v.contains("grid")) {
    const json& g = v["grid"];
    if (!g.is_object()) r.fail(where + "/grid", "must be an object: option -> array of values");
    for (const auto& [name, values] : g.items()) {
      const std::string at = where + "/grid/" + name;
      if (!values.is_array() || values.empty()) r.fail(at, "must be a non-empty array of values");
      OptionList probe;
      std::vector<json> list;
      for (std::size_t i = 0; i < values.size(); ++i) {
        readOptions(r, json{{name, values[i]}}, fmt::format("{}/{}", where + "/grid", i), probe);
        list.push_back(values[i]);
      }
      e.grid.emplace_back(name, std::move(list));
    }
  }
  return e;
}

PlotSpec readPlot(const Reader& r, const json& v, const std::string& where) {
  r.onlyKeys(v, where,
             {"out", "results", "kind", "layout", "titles", "labels", "approaches", "metric", "marks", "at-step",
              "title", "xlabel", "ylabel", "ymin", "ymax", "width", "height"});
  PlotSpec p;
  p.where = where;
  if (!v.contains("out") || !v.contains("results")) r.fail(where, "a plot needs \"out\" and \"results\"");
  p.out = r.text(v["out"], where + "/out");
  const std::string ext = fs::path(p.out).extension().string();
  if (ext != ".png" && ext != ".svg" && ext != ".pdf") r.fail(where + "/out", "must end in .png, .svg or .pdf");
  p.results = r.texts(v["results"], where + "/results");
  if (p.results.empty()) r.fail(where + "/results", "names no experiment");
  plot::FigureRequest& q = p.request;
  if (v.contains("kind")) {
    const std::string kind = r.text(v["kind"], where + "/kind");
    if (kind != "lines" && kind != "bars") r.fail(where + "/kind", "must be \"lines\" or \"bars\"");
    q.kind = kind == "bars" ? plot::ChartKind::Bars : plot::ChartKind::Lines;
  }
  if (v.contains("layout")) {
    const std::string layout = r.text(v["layout"], where + "/layout");
    if (layout != "panels" && layout != "together") r.fail(where + "/layout", "must be \"panels\" or \"together\"");
    q.together = layout == "together";
  }
  if (v.contains("titles")) q.titles = r.texts(v["titles"], where + "/titles");
  if (v.contains("labels")) q.labels = r.texts(v["labels"], where + "/labels");
  if (v.contains("approaches")) q.approaches = r.texts(v["approaches"], where + "/approaches");
  if (v.contains("metric")) {
    const auto m = plot::parseMetric(r.text(v["metric"], where + "/metric"));
    if (!m) r.fail(where + "/metric", "must be \"eval\", \"success\" or \"preferences\"");
    q.metric = *m;
  }
  if (v.contains("marks")) {
    if (!v["marks"].is_array()) r.fail(where + "/marks", "must be an array of training steps");
    for (std::size_t i = 0; i < v["marks"].size(); ++i)
      q.marks.push_back(r.number(v["marks"][i], fmt::format("{}/marks/{}", where, i)));
  }
  if (v.contains("at-step")) q.atStep = r.count(v["at-step"], where + "/at-step", 0);
  if (v.contains("title")) q.title = r.text(v["title"], where + "/title");
  if (v.contains("xlabel")) q.xLabel = r.text(v["xlabel"], where + "/xlabel");
  if (v.contains("ylabel")) q.yLabel = r.text(v["ylabel"], where + "/ylabel");
  if (v.contains("ymin")) q.yMin = r.number(v["ymin"], where + "/ymin");
  if (v.contains("ymax")) q.yMax = r.number(v["ymax"], where + "/ymax");
  if (v.contains("width")) q.panelWidth = r.number(v["width"], where + "/width");
  if (v.contains("height")) q.panelHeight = r.number(v["height"], where + "/height");
  return p;
}

SlurmSpec readSlurm(const Reader& r, const json& v) {
  const std::string where = "/slurm";
  r.onlyKeys(
      v, where,
      {"partition", "time", "mem", "cpus-per-task", "array-limit", "trials-per-task", "max-array-size", "sbatch"});
  SlurmSpec s;
  if (v.contains("partition")) s.partition = r.text(v["partition"], where + "/partition");
  if (v.contains("time")) s.time = r.text(v["time"], where + "/time");
  if (v.contains("mem")) s.mem = r.text(v["mem"], where + "/mem");
  if (v.contains("cpus-per-task")) s.cpusPerTask = r.count(v["cpus-per-task"], where + "/cpus-per-task", 1);
  if (v.contains("array-limit")) s.arrayLimit = r.count(v["array-limit"], where + "/array-limit", 0);
  if (v.contains("trials-per-task")) s.trialsPerTask = r.count(v["trials-per-task"], where + "/trials-per-task", 1);
  if (v.contains("max-array-size")) s.maxArraySize = r.count(v["max-array-size"], where + "/max-array-size", 1);
  if (v.contains("sbatch")) s.sbatch = r.texts(v["sbatch"], where + "/sbatch");
  for (std::size_t i = 0; i < s.sbatch.size(); ++i)
    if (s.sbatch[i].rfind("--", 0) != 0 || s.sbatch[i].find('\n') != std::string::npos)
      r.fail(fmt::format("{}/sbatch/{}", where, i), "an sbatch option on one line, starting with --");
  return s;
}

}  // namespace

bool parseSeedList(const std::string& text, std::vector<std::uint64_t>& seeds) {
  const auto whole = [](const std::string& s, std::uint64_t& v) {
    if (s.empty() || s.size() > 19 || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }))
      return false;
    v = std::stoull(s);
    return true;
  };
  seeds.clear();
  if (const auto dots = text.find(".."); dots != std::string::npos) {
    std::uint64_t lo = 0, hi = 0;
    if (!whole(text.substr(0, dots), lo) || !whole(text.substr(dots + 2), hi) || lo > hi || hi - lo > 10000)
      return false;
    for (auto s = lo; s <= hi; ++s) seeds.push_back(s);
    return true;
  }
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    std::uint64_t v = 0;
    if (!whole(item, v)) return false;
    seeds.push_back(v);
  }
  return !seeds.empty() && seeds.size() <= 10001;
}

SweepConfig readSweepConfig(const std::string& path) {
  std::string text;
  try {
    text = support::readInputFile(path, support::kMaxDataBytes, "sweep configuration");
  } catch (const support::InputFileError& e) {
    throw SweepError(e.kind == support::InputFileError::Kind::CannotOpen ? fmt::format("{}: no such file", path)
                                                                         : std::string(e.what()));
  }
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw SweepError(fmt::format("{}: not JSON: {}", path, e.what()));
  }
  const Reader r(path);
  r.onlyKeys(root, "", {"name", "out", "defaults", "experiments", "plots", "slurm"});
  SweepConfig c;
  c.path = fs::absolute(path).lexically_normal().string();
  const fs::path base = fs::path(c.path).parent_path();
  c.name = root.contains("name") ? r.text(root["name"], "/name") : fs::path(path).stem().string();
  if (!safeName(c.name)) r.fail("/name", "use letters, digits, '.', '_' and '-'");
  c.out = root.contains("out") ? r.text(root["out"], "/out") : "sweep-" + c.name;
  OptionList defaults;
  if (root.contains("defaults")) readOptions(r, root["defaults"], "/defaults", defaults);
  if (!root.contains("experiments") || !root["experiments"].is_array() || root["experiments"].empty())
    r.fail("/experiments", "needs an array of at least one experiment");
  std::set<std::string> names;
  for (std::size_t i = 0; i < root["experiments"].size(); ++i) {
    const std::string where = fmt::format("/experiments/{}", i);
    c.experiments.push_back(readExperiment(r, root["experiments"][i], where, base, defaults));
    if (!names.insert(c.experiments.back().name).second)
      r.fail(where + "/name", "another experiment has this name: " + c.experiments.back().name);
  }
  if (root.contains("plots")) {
    if (!root["plots"].is_array()) r.fail("/plots", "must be an array");
    for (std::size_t i = 0; i < root["plots"].size(); ++i)
      c.plots.push_back(readPlot(r, root["plots"][i], fmt::format("/plots/{}", i)));
  }
  if (root.contains("slurm")) c.slurm = readSlurm(r, root["slurm"]);
  return c;
}

}  // namespace cbtl::sweep
