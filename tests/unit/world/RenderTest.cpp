// Offscreen rendering produces a non-empty image of the arm. Without EGL the whole executable exits with 77
// (CTest's SKIP_RETURN_CODE) instead of failing.
#include "robot/world/PngWriter.h"
#include "robot/world/Renderer.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

namespace cbtl::world {
namespace {

std::unique_ptr<OffscreenRenderer> gRenderer;

TEST(WorldRender, FeedingSceneShowsTheArm) {
  Workspace ws(test::feedingScene());
  ws.setArm(configs::kHome);
  Image img;
  ASSERT_EQ(gRenderer->render(ws, {}, 320, 240, img), RenderStatus::Ok);
  ASSERT_EQ(img.rgb.size(), 320U * 240U * 3U);
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    colours.insert((std::uint32_t{img.rgb[i]} << 16) | (std::uint32_t{img.rgb[i + 1]} << 8) | img.rgb[i + 2]);
  EXPECT_GT(colours.size(), 50U) << "the image looks blank";

  // Moving the arm changes the picture.
  Image other;
  ws.setArm(configs::kZero);
  ASSERT_EQ(gRenderer->render(ws, {}, 320, 240, other), RenderStatus::Ok);
  EXPECT_NE(img.rgb, other.rgb);

  const auto path = std::filesystem::temp_directory_path() / "cbtl_world_render_test.png";
  ASSERT_TRUE(writePng(path.string(), img.width, img.height, img.rgb));
  // Compressed, and losslessly: the file reads back as the rendered pixels.
  EXPECT_LT(std::filesystem::file_size(path), 320U * 240U * 3U / 4);
  std::ifstream file(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto decoded = decodePng(bytes);
  ASSERT_TRUE(decoded.has_value());
  EXPECT_EQ(decoded->rgb, img.rgb);
  std::filesystem::remove(path);
}

TEST(WorldRender, UnknownCameraAndOversizeAreReported) {
  Workspace ws(test::feedingScene());
  Image img;
  CameraSpec cam;
  cam.name = "no_such_camera";
  EXPECT_EQ(gRenderer->render(ws, cam, 64, 48, img), RenderStatus::UnknownCamera);
  EXPECT_EQ(gRenderer->render(ws, {}, 100000, 48, img), RenderStatus::TooLarge);
}

}  // namespace
}  // namespace cbtl::world

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  cbtl::world::RenderStatus status{};
  std::string message;
  cbtl::world::gRenderer = cbtl::world::OffscreenRenderer::create(cbtl::world::test::feedingScene(), status, message);
  if (!cbtl::world::gRenderer) {
    std::fprintf(stderr, "skipping rendering tests: %s: %s\n", cbtl::world::toString(status), message.c_str());
    return 77;
  }
  const int rc = RUN_ALL_TESTS();
  cbtl::world::gRenderer.reset();
  return rc;
}
