// `cbtl render SCENE [--state FILE.json] --out FILE.png`: a picture of any robot scene in any state,
// rendered offscreen (EGL, no display needed). Exit codes: 0 ok, 1 bad input (scene, state or output file),
// 2 usage, 70 internal error (including no usable EGL/OpenGL).
#include "tools/cbtl/CommandRegistry.h"
#include "tools/cbtl/ErrorHandling.h"
#include "tools/cbtl/OptionChecks.h"

#include "robot/world/PngWriter.h"
#include "robot/world/Renderer.h"
#include "robot/world/StateJson.h"
#include "robot/world/Workspace.h"

#include <fmt/core.h>

#include <memory>
#include <string>

namespace {

struct RenderArgs {
  std::string scene;
  std::string state;
  std::string out;
  std::string camera;
  int width = 640;
  int height = 480;
  double azimuth = 150.0;
  double elevation = -25.0;
  double distance = 0.0;
};

int runRender(const RenderArgs& a) {
  using namespace cbtl::world;
  const SceneLoadResult loaded = Scene::loadFile(a.scene);
  if (loaded.status != LoadStatus::Ok) {
    fmt::print(stderr, "cbtl render: error: {}\n", loaded.message);
    return 1;
  }
  Workspace ws(loaded.scene);
  if (!a.state.empty()) {
    const StateJsonResult st = applyStateFile(ws, a.state);
    if (st.status != StateJsonStatus::Ok) {
      fmt::print(stderr, "cbtl render: error: {}\n", st.message);
      return 1;
    }
  }
  RenderStatus status{};
  std::string message;
  auto renderer = OffscreenRenderer::create(loaded.scene, status, message);
  if (!renderer) {
    fmt::print(stderr, "cbtl render: error: cannot render offscreen: {}: {}\n", toString(status), message);
    return 70;
  }
  CameraSpec cam;
  cam.name = a.camera;
  cam.azimuth = a.azimuth;
  cam.elevation = a.elevation;
  if (a.distance > 0) cam.distance = a.distance;
  Image img;
  status = renderer->render(ws, cam, a.width, a.height, img);
  if (status == RenderStatus::UnknownCamera) {
    fmt::print(stderr, "cbtl render: error: {}: the scene has no camera named '{}'\n", a.scene, a.camera);
    return 1;
  }
  if (status == RenderStatus::TooLarge) {
    fmt::print(stderr,
               "cbtl render: error: {}x{} exceeds the scene's offscreen buffer {}x{} (set <visual><global "
               "offwidth/offheight> in {})\n",
               a.width, a.height, renderer->maxWidth(), renderer->maxHeight(), a.scene);
    return 1;
  }
  if (status != RenderStatus::Ok) {
    fmt::print(stderr, "cbtl render: error: {}\n", toString(status));
    return 70;
  }
  if (!writePng(a.out, img.width, img.height, img.rgb)) {
    fmt::print(stderr, "cbtl render: error: {}: cannot write the image\n", a.out);
    return 1;
  }
  fmt::print("wrote {} ({}x{})\n", a.out, img.width, img.height);
  return 0;
}

}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a robot scene (and optionally a state) to a PNG image");
  cmd->add_option("scene", args->scene, "MuJoCo scene file (e.g. domains/feeding/feeding.xml)")->required();
  cmd->add_option("--state", args->state,
                  "JSON state: arm joints, base pose, object poses, fixture poses, held object");
  cmd->add_option("--out,-o", args->out, "output PNG file")->required();
  cmd->add_option("--camera", args->camera, "a named camera of the scene (default: free camera)");
  cmd->add_option("--width", args->width, "image width in pixels")->check(CLI::Range(1, 8192));
  cmd->add_option("--height", args->height, "image height in pixels")->check(CLI::Range(1, 8192));
  cmd->add_option("--azimuth", args->azimuth, "free camera azimuth, degrees")->check(cbtl::cli::realIn(-360, 360));
  cmd->add_option("--elevation", args->elevation, "free camera elevation, degrees")->check(cbtl::cli::realIn(-90, 90));
  cmd->add_option("--distance", args->distance, "free camera distance, metres (default, or 0: from the scene)")
      ->check(cbtl::cli::realIn(0, 1e6));
  cmd->callback([args, &exitCode] { cbtl::cli::runCommand("render", exitCode, [&] { return runRender(*args); }); });
}

static cbtl::cli::RegisterCommand reg(50, addRenderCommand);
