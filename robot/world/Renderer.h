// Renderer.h — offscreen rendering of a Workspace's state to an RGB image, headless, through EGL (Mesa's
// surfaceless platform works without a GPU or X server) and MuJoCo's OpenGL renderer.
//
// Thread safety: the GL context is current on the thread that created the renderer; use a renderer only on
// that thread, and one renderer per thread. The largest image is the scene's <visual><global offwidth
// offheight> (1280 x 960 in our scenes).
// Cameras: a named <camera> of the scene, or a free camera looking at `lookat` (default: the scene's
// <statistic center>) from `distance` (default 1.6 x <statistic extent>) at azimuth/elevation in degrees.
#pragma once

#include "robot/world/Workspace.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cbtl::world {

enum class RenderStatus {
  Ok,
  EglUnavailable,  // no EGL display could be initialised (no libEGL / driver): callers may skip
  ContextFailed,   // EGL or MuJoCo could not create an OpenGL context, or it could not be made current
  UnknownCamera,   // no camera with the requested name
  TooLarge,        // the requested size exceeds the scene's offscreen buffer
};

const char* toString(RenderStatus s);

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3, rows top to bottom
};

struct CameraSpec {
  std::string name;  // a fixed camera of the scene; empty: free camera
  std::optional<Eigen::Vector3d> lookat;
  std::optional<double> distance;  // m
  double azimuth = 150.0;          // degrees
  double elevation = -25.0;        // degrees
};

class OffscreenRenderer {
 public:
  // Creates an EGL context and MuJoCo's GPU resources for the scene. On failure returns null and sets
  // status and message.
  static std::unique_ptr<OffscreenRenderer> create(std::shared_ptr<const Scene> scene, RenderStatus& status,
                                                   std::string& message);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  // Renders the Workspace's current state. `ws` must be over the renderer's scene. Callable from any thread, one
  // thread at a time: the OpenGL context is made current for the call and released after it (ContextFailed when it
  // cannot be made current).
  RenderStatus render(Workspace& ws, const CameraSpec& camera, int width, int height, Image& out);

  int maxWidth() const;
  int maxHeight() const;

 private:
  OffscreenRenderer() = default;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cbtl::world
