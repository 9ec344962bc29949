#include "robot/world/Renderer.h"

#include "robot/world/MujocoErrors.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <fmt/core.h>

#include <algorithm>
#include <cstring>

namespace cbtl::world {

const char* toString(RenderStatus s) {
  switch (s) {
    case RenderStatus::Ok:
      return "ok";
    case RenderStatus::EglUnavailable:
      return "EGL unavailable";
    case RenderStatus::ContextFailed:
      return "OpenGL context creation failed";
    case RenderStatus::UnknownCamera:
      return "unknown camera";
    case RenderStatus::TooLarge:
      return "image larger than the offscreen buffer";
  }
  return "unknown";
}

struct OffscreenRenderer::Impl {
  std::shared_ptr<const Scene> scene;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  bool mjrReady = false;
  bool mjvReady = false;
  mjrContext con;
  mjvScene scn;
  mjvOption opt;

  ~Impl() {
    if (display != EGL_NO_DISPLAY && context != EGL_NO_CONTEXT)
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context);  // mjr_freeContext needs it current
    if (mjvReady) mjv_freeScene(&scn);
    if (mjrReady) mjr_freeContext(&con);
    if (display != EGL_NO_DISPLAY) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
      // The display is left initialized for the process (EGL displays are per process, and the next renderer
      // initializes the same one again): terminating it unloads the driver, whose bookkeeping of the threads
      // that rendered then points nowhere (LeakSanitizer reports it, from an unknown module).
    }
  }
};

namespace {

// Mesa's surfaceless platform first (no display server needed), then the default display.
EGLDisplay openDisplay() {
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLint major = 0, minor = 0;
  if (getPlatformDisplay) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
  return EGL_NO_DISPLAY;
}

}  // namespace

std::unique_ptr<OffscreenRenderer> OffscreenRenderer::create(std::shared_ptr<const Scene> scene, RenderStatus& status,
                                                             std::string& message) {
  installMujocoHandlers();
  std::unique_ptr<OffscreenRenderer> r(new OffscreenRenderer());
  r->impl_ = std::make_unique<Impl>();
  Impl& im = *r->impl_;
  im.scene = std::move(scene);
  im.display = openDisplay();
  if (im.display == EGL_NO_DISPLAY) {
    status = RenderStatus::EglUnavailable;
    message = "no EGL display (surfaceless or default) could be initialised";
    return nullptr;
  }
  // The surfaceless platform offers no configs unless pbuffer support is requested.
  const EGLint attribs[] = {EGL_RED_SIZE,
                            8,
                            EGL_GREEN_SIZE,
                            8,
                            EGL_BLUE_SIZE,
                            8,
                            EGL_ALPHA_SIZE,
                            8,
                            EGL_DEPTH_SIZE,
                            24,
                            EGL_STENCIL_SIZE,
                            8,
                            EGL_RENDERABLE_TYPE,
                            EGL_OPENGL_BIT,
                            EGL_SURFACE_TYPE,
                            EGL_PBUFFER_BIT,
                            EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(im.display, attribs, &config, 1, &count) || count < 1) {
    status = RenderStatus::ContextFailed;
    message = "EGL offers no RGBA8/depth24 OpenGL config";
    return nullptr;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    status = RenderStatus::ContextFailed;
    message = "EGL cannot bind the desktop OpenGL API";
    return nullptr;
  }
  im.context = eglCreateContext(im.display, config, EGL_NO_CONTEXT, nullptr);
  if (im.context == EGL_NO_CONTEXT || !eglMakeCurrent(im.display, EGL_NO_SURFACE, EGL_NO_SURFACE, im.context)) {
    status = RenderStatus::ContextFailed;
    message = fmt::format("EGL context creation failed (error 0x{:x})", eglGetError());
    return nullptr;
  }
  const mjModel* m = im.scene->model();
  try {
    mjv_defaultOption(&im.opt);
    mjv_defaultScene(&im.scn);
    mjv_makeScene(m, &im.scn, 2000);
    im.mjvReady = true;
    mjr_defaultContext(&im.con);
    mjr_makeContext(m, &im.con, mjFONTSCALE_100);
    im.mjrReady = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &im.con);
  } catch (const MujocoError& e) {
    status = RenderStatus::ContextFailed;
    message = e.what();
    return nullptr;
  }
  if (im.con.currentBuffer != mjFB_OFFSCREEN) {
    status = RenderStatus::ContextFailed;
    message = "MuJoCo could not select its offscreen buffer";
    return nullptr;
  }
  // Released, so that render() can make it current in whichever thread calls it (a context is current in one
  // thread at most; a server renders on its request threads).
  eglMakeCurrent(im.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  status = RenderStatus::Ok;
  message.clear();
  return r;
}

OffscreenRenderer::~OffscreenRenderer() = default;

int OffscreenRenderer::maxWidth() const { return impl_->con.offWidth; }
int OffscreenRenderer::maxHeight() const { return impl_->con.offHeight; }

RenderStatus OffscreenRenderer::render(Workspace& ws, const CameraSpec& camera, int width, int height, Image& out) {
  Impl& im = *impl_;
  const mjModel* m = im.scene->model();
  if (width <= 0 || height <= 0 || width > im.con.offWidth || height > im.con.offHeight) return RenderStatus::TooLarge;
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  if (!camera.name.empty()) {
    const int id = mj_name2id(m, mjOBJ_CAMERA, camera.name.c_str());
    if (id < 0) return RenderStatus::UnknownCamera;
    cam.type = mjCAMERA_FIXED;
    cam.fixedcamid = id;
  } else {
    cam.type = mjCAMERA_FREE;
    const Eigen::Vector3d look =
        camera.lookat.value_or(Eigen::Vector3d(m->stat.center[0], m->stat.center[1], m->stat.center[2]));
    for (int i = 0; i < 3; ++i) cam.lookat[i] = look[i];
    cam.distance = camera.distance.value_or(1.6 * m->stat.extent);
    cam.azimuth = camera.azimuth;
    cam.elevation = camera.elevation;
  }
  if (!eglMakeCurrent(im.display, EGL_NO_SURFACE, EGL_NO_SURFACE, im.context)) return RenderStatus::ContextFailed;
  // Released on every return below, as after create().
  struct Release {
    EGLDisplay display;
    ~Release() { eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }
  } release{im.display};
  mj_camlight(m, ws.data());  // camera and light poses (mj_kinematics does not compute them)
  mjv_updateScene(m, ws.data(), &im.opt, nullptr, &cam, mjCAT_ALL, &im.scn);
  const mjrRect viewport{0, 0, width, height};
  mjr_render(viewport, &im.scn, &im.con);
  std::vector<std::uint8_t> flipped(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  mjr_readPixels(flipped.data(), nullptr, viewport, &im.con);
  // OpenGL rows run bottom-up.
  out.width = width;
  out.height = height;
  out.rgb.resize(flipped.size());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::memcpy(out.rgb.data() + static_cast<std::size_t>(y) * row,
                flipped.data() + static_cast<std::size_t>(height - 1 - y) * row, row);
  return RenderStatus::Ok;
}

}  // namespace cbtl::world
