// `cbtl study simulate` and `cbtl study demo`: the paper's web study with simulated participants and its
// real-robot demonstration, in the Feeding domain (domains/feeding/FeedingStudy.h, FeedingDemo.h).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/RuntimeSupport.h"
#include "tools/cbtl/StudyCommands.h"

#include "domains/feeding/FeedingDemo.h"
#include "domains/feeding/FeedingStudy.h"
#include "robot/world/PngWriter.h"
#include "robot/world/Renderer.h"

#include <fmt/core.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace feeding = cbtl::domains::feeding;

using cbtl::cli::StudyArgs;

// An output folder for files `names`: created when missing; refused when one of them is there, unless --force.
bool prepareOut(const char* command, const StudyArgs& a, const std::vector<std::string>& names) {
  if (a.out.empty()) return true;
  std::filesystem::create_directories(a.out);
  for (const auto& name : names) {
    if (std::filesystem::exists(std::filesystem::path(a.out) / name) && !a.force) {
      fmt::print(stderr, "cbtl {}: error: {} already holds {} (use --force to replace it)\n", command, a.out, name);
      return false;
    }
  }
  return true;
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  if (!f) throw std::runtime_error(path + ": cannot write");
}

int runSimulate(const StudyArgs& a) {
  if (!a.inProcess) return cbtl::cli::runStudySimulateOverHttp(a);
  feeding::StudyOptions options;
  auto lp = cbtl::cli::loadFeedingStudy("study simulate", a, options);
  if (!lp) return 1;
  if (!prepareOut("study simulate", a, {"study.csv", "meals.csv"})) return 1;
  options.participants = a.participants;
  options.firstParticipant = a.firstParticipant;
  const feeding::StudyResult r = feeding::runStudy(*lp, cbtl::app::simulatorFacts(*lp), options);
  fmt::print("study: {} simulated participants (from {}), five meals, CBTL{} against No Personalization\n",
             a.participants, a.firstParticipant,
             options.askExploringView ? " (asking about its most uncertain view)" : "");
  fmt::print("{:<5} {:<16} {:<12} {:<14} | {:^27} | {:^27} | {}\n", "meal", "setting", "table", "food",
             "CBTL: dip sig verb view bite", "NP:   dip sig verb view bite", "CBTL better / tied / worse");
  std::string csv = "meal,food,setting,table,approach";
  for (const auto& p : feeding::studyPreferences()) csv += "," + p + "_met_rate";
  csv += ",cbtl_better,tied,cbtl_worse\n";
  for (std::size_t k = 0; k < r.meals.size(); ++k) {
    const auto& m = r.meals[k];
    std::string cells[2];
    for (int i = 0; i < 2; ++i) {
      const std::string& name = feeding::studyApproaches()[static_cast<std::size_t>(i)];
      const auto& met = m.met.at(name);
      for (const char* p : {"dip", "signal", "verbosity", "view", "bite"})
        cells[i] += fmt::format(" {:.2f}", met.at(p).rate());
      csv += fmt::format("{},{},{},{},{}", k + 1, m.meal.food, m.meal.setting, m.meal.table, name);
      for (const auto& p : feeding::studyPreferences()) csv += fmt::format(",{:.6g}", met.at(p).rate());
      csv += fmt::format(",{},{},{}\n", m.cbtlBetter, m.tied, m.cbtlWorse);
    }
    fmt::print("{:<5} {:<16} {:<12} {:<14} | {:<27} | {:<27} | {} / {} / {}\n", k + 1, m.meal.setting, m.meal.table,
               m.meal.food, cells[0], cells[1], m.cbtlBetter, m.tied, m.cbtlWorse);
  }
  fmt::print("{} solutions re-checked before execution, {} refused\n", r.rechecks, r.recheckViolations);
  if (!a.out.empty()) {
    writeFile(a.out + "/study.csv", feeding::studyCsv(r));
    writeFile(a.out + "/meals.csv", csv);
    fmt::print("wrote {}/study.csv, meals.csv\n", a.out);
  }
  return r.recheckViolations == 0 ? 0 : 70;
}

std::string xy(const std::vector<double>& v) {
  return v.size() == 2 ? fmt::format("({:.3f}, {:.3f})", v[0], v[1]) : "-";
}

// Pictures of trial 1: the scene from the overview camera and the user's view, per approach and request.
class DemoPictures {
 public:
  DemoPictures(const StudyArgs& a, std::shared_ptr<const cbtl::world::Scene> scene) : args_(a) {
    if (a.out.empty() || a.noPictures || !scene) return;
    cbtl::world::RenderStatus status{};
    std::string message;
    renderer_ = cbtl::world::OffscreenRenderer::create(std::move(scene), status, message);
    if (!renderer_)
      fmt::print(stderr, "cbtl study demo: no pictures: {}: {}\n", cbtl::world::toString(status), message);
  }
  void operator()(int trial, const std::string& approach, const feeding::DemoStep& step,
                  feeding::FeedingSimulator& world) {
    if (!renderer_ || trial != 0 || !step.conf) return;
    cbtl::world::Workspace& ws = world.world().workspace();
    const cbtl::world::WorldState keep = ws.state();
    ws.setState(feeding::demoStepState(world, step));
    std::string request = step.request;
    std::replace(request.begin(), request.end(), ' ', '-');
    for (const char* camera : {"overview", "user_view"}) {
      cbtl::world::CameraSpec spec;
      spec.name = camera;
      cbtl::world::Image img;
      if (renderer_->render(ws, spec, args_.width, args_.height, img) != cbtl::world::RenderStatus::Ok) continue;
      const std::string path = fmt::format("{}/{}-{}-{}.png", args_.out, approach, request,
                                           std::string(camera) == "overview" ? "scene" : "view");
      if (cbtl::world::writePng(path, img.width, img.height, img.rgb)) written_.push_back(path);
    }
    ws.setState(keep);
  }
  const std::vector<std::string>& written() const { return written_; }

 private:
  const StudyArgs& args_;
  std::unique_ptr<cbtl::world::OffscreenRenderer> renderer_;
  std::vector<std::string> written_;
};

int runDemoCommand(const StudyArgs& a) {
  feeding::DemoOptions options;
  auto lp = cbtl::cli::loadFeedingStudy("study demo", a, options.study);
  if (!lp) return 1;
  std::vector<std::string> pictures;
  for (const auto& approach : feeding::studyApproaches())
    for (const char* request : {"bite-1", "bite-2", "drink-1"})
      for (const char* kind : {"scene", "view"})
        pictures.push_back(fmt::format("{}-{}-{}.png", approach, request, kind));
  if (!prepareOut("study demo", a, pictures)) return 1;
  options.participant = a.participant;
  options.trials = a.trials;
  options.seed = a.seed;
  const auto facts = cbtl::app::simulatorFacts(*lp);
  std::shared_ptr<const cbtl::world::Scene> scene = facts.scene;
  if (!scene) scene = cbtl::world::Scene::loadFile(facts.scenePath).scene;
  DemoPictures pics(a, scene);
  const feeding::DemoResult r = feeding::runDemo(*lp, facts, options, std::ref(pics));
  fmt::print(
      "demonstration: participant {} (occlusion threshold {:.3f}, hidden from the robot) had meals 1-4 in the "
      "study; meal 5: {}, {} and {}, {}, {} table\n",
      a.participant, r.threshold, r.meal.food, r.meal.dips.at(0), r.meal.dips.at(1), r.meal.setting, r.meal.table);
  for (std::size_t t = 0; t < r.trials.size(); ++t) {
    if (t == 0) {
      fmt::print("trial 1:\n  {:<8} {:<19} {:<35} {:<35} {:>9}  {:<9} {:<12} {:<8} {}\n", "request", "approach",
                 "plate (from -> to)", "drink (from -> to)", "occlusion", "dip", "signal", "talk", "complaints");
      for (const auto& approach : feeding::studyApproaches()) {
        for (const auto& s : r.trials[t].steps.at(approach)) {
          fmt::print("  {:<8} {:<19} {:<35} {:<35} {:>9} {:<9} {:<12} {:<8} {}{}\n", s.request, approach,
                     xy(s.plateFrom) + " -> " + xy(s.plateTo), xy(s.drinkFrom) + " -> " + xy(s.drinkTo),
                     s.conf ? fmt::format("{:.3f}", s.occlusion) : "-", s.dip.empty() ? "-" : s.dip,
                     s.signal.empty() ? "-" : s.signal, s.verbosity.empty() ? "-" : s.verbosity, s.complaints,
                     s.solved ? "" : "  (not carried out)");
        }
      }
    }
  }
  fmt::print("complaints at (bite 1, bite 2, drink 1), per trial:\n");
  for (const auto& approach : feeding::studyApproaches()) {
    fmt::print("  {:<19}", approach);
    for (const auto& trial : r.trials) {
      const auto& s = trial.steps.at(approach);
      fmt::print(" ({}, {}, {})", s.at(0).complaints, s.at(1).complaints, s.at(3).complaints);
    }
    fmt::print("\n");
  }
  fmt::print("the reference's real robot, 5 trials: CBTL (1, 0, 0) and without learning (1, 1, 1) in every trial\n");
  for (const auto& p : pics.written()) fmt::print("wrote {}\n", p);
  return 0;
}

void addStudy(CLI::App& app, int& exitCode) {
  CLI::App* study =
      app.add_subcommand("study", "the paper's Feeding web study and real-robot demonstration, simulated");
  study->require_subcommand(1);
  auto args = std::make_shared<StudyArgs>();
  CLI::App* sim =
      study->add_subcommand("simulate", "five meals with simulated participants: CBTL against No Personalization");
  CLI::App* demo =
      study->add_subcommand("demo", "meal 5 after meals 1-4: plate and drink in front, complaints and pictures");
  CLI::App* serve = study->add_subcommand(
      "serve", "the web study: pages and JSON API for participants at /p/<id>, CBTL learning from their answers");
  for (CLI::App* cmd : {sim, demo, serve}) {
    cmd->add_option("file", args->file, "the Feeding program (domains/feeding/feeding.cbtl)")->required();
    cmd->add_option("--seed", args->seed, "seed of every random choice")->capture_default_str();
    if (cmd != serve) {
      cmd->add_option("--out", args->out, "output folder");
      cmd->add_flag("--force", args->force, "replace the files of an earlier run in --out");
    }
    cmd->add_flag("--no-exploring-view", args->noExploringView,
                  "CBTL learns from its shown choices only (no question about its most uncertain view)");
    cmd->add_option("--stdlib", args->stdlibDir, "standard library folder (default: embedded)");
    cbtl::cli::addSolverOptions(cmd, args->solver);
    cbtl::cli::addTextBackendOptions(cmd, args->text);
  }
  sim->add_option("--participants", args->participants, "simulated participants")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sim->add_option("--first-participant", args->firstParticipant, "the first participant's number")
      ->check(CLI::Range(0, 1000000000));
  sim->add_flag("--in-process", args->inProcess,
                "run the study inside this process, without the server, judging by each preference met (the "
                "simulator's own tables: study.csv, meals.csv)");
  sim->add_option("--db", args->db, "the study database to write (default: <out>/study.sqlite, or a temporary one)");
  sim->add_option("--jobs", args->jobs, "participants taking the study at once (results do not depend on it)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  demo->add_option("--participant", args->participant, "the simulated participant")->check(CLI::Range(0, 1000000000));
  demo->add_option("--trials", args->trials, "trials (seed, seed + 1, ...)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  demo->add_option("--width", args->width, "picture width in pixels")->check(CLI::Range(16, 1280));
  demo->add_option("--height", args->height, "picture height in pixels")->check(CLI::Range(16, 960));
  demo->add_flag("--no-pictures", args->noPictures, "do not render pictures");
  serve->add_option("--db", args->db, "the study's database (SQLite; created when missing)")->required();
  serve->add_option("--host", args->host, "address to listen on (other than 127.0.0.1: reachable from elsewhere)")
      ->capture_default_str();
  serve->add_option("--port", args->port, "port to listen on (0: any free port, printed)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  serve->add_flag("--no-pictures", args->noPictures, "do not render the view pictures (they are answered 503)");
  serve->add_option("--study-info", args->studyInfo,
                    "JSON file with the study's title, researcher, institution, contact, ethics_approval and consent "
                    "paragraphs, shown to participants (docs/study.md)");
  serve
      ->add_option("--max-sessions", args->maxSessions,
                   "participants' sessions kept in memory (about 27 MB each); the least recently used beyond are "
                   "rebuilt from the database when needed")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  serve
      ->add_option("--max-participants", args->maxParticipants,
                   "participants the study admits in all (0: no limit); beyond, a new one is told the study is full")
      ->check(CLI::Range(0, 100000000))
      ->capture_default_str();
  serve
      ->add_option("--new-participants-per-minute", args->newParticipantsPerMinute,
                   "new participants admitted a minute on average, up to 60 at once (0: no limit); also bounds the "
                   "trying of participant ids")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  serve
      ->add_option("--planners", args->planners,
                   "copies of the program that plan participants' meals in parallel (0: one per core, at most 8)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  serve->add_option("--connections", args->connections, "requests answered at once (threads); a slow client holds one")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  serve->add_option("--picture-width", args->width, "picture width in pixels")
      ->check(CLI::Range(16, 1280))
      ->capture_default_str();
  serve->add_option("--picture-height", args->height, "picture height in pixels")
      ->check(CLI::Range(16, 960))
      ->capture_default_str();
  sim->callback(
      [args, &exitCode] { cbtl::cli::runCommand("study simulate", exitCode, [&] { return runSimulate(*args); }); });
  serve->callback([args, &exitCode] {
    cbtl::cli::runCommand("study serve", exitCode, [&] { return cbtl::cli::runStudyServe(*args); });
  });
  demo->callback(
      [args, &exitCode] { cbtl::cli::runCommand("study demo", exitCode, [&] { return runDemoCommand(*args); }); });
}

}  // namespace

namespace cbtl::cli {

std::unique_ptr<app::LoadedProgram> loadFeedingStudy(const char* command, const StudyArgs& a,
                                                     domains::feeding::StudyOptions& options) {
  auto lp = loadForRun(command, a.file, a.stdlibDir);
  if (!lp) return nullptr;
  if (lp->graph().domain != "feeding") {
    fmt::print(stderr, "cbtl {}: error: {}: the study is the Feeding domain's; this program is domain '{}'\n", command,
               a.file, lp->graph().domain);
    return nullptr;
  }
  const auto backend = makeTextBackend(command, a.text);
  if (!backend) return nullptr;
  options.textBackend = *backend;
  options.solver = solverOptionsFor(a.solver, "feeding");
  options.seed = a.seed;
  options.askExploringView = !a.noExploringView;
  return lp;
}

}  // namespace cbtl::cli

const cbtl::cli::RegisterCommand registerStudy(25, addStudy);
