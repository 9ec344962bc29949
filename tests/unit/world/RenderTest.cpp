// Offscreen rendering produces a non-empty image of the arm. Without EGL the whole executable exits with 77
// (CTest's SKIP_RETURN_CODE) instead of failing.
#include "robot/world/PngWriter.h"
#include "robot/world/Renderer.h"
#include "tests/unit/world/WorldTestSupport.h"

#include <gtest/gtest.h>

#include <array>
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

// The study's pictures are taken by the user_view camera: a participant sees a room (no black void), the plate on
// the table near the bottom, and across the table the friend and the TV of the meal's setting, which the
// simulator parks under the floor when the setting does not name them.
TEST(WorldRender, TheUsersViewShowsTheRoomThePlateAndTheSettingsCompany) {
  Workspace ws(test::feedingScene());
  CameraSpec cam;
  cam.name = "user_view";
  const int w = 320, h = 240;
  Image company, alone;
  ASSERT_EQ(gRenderer->render(ws, cam, w, h, company), RenderStatus::Ok);
  for (const char* fixture : {"friend", "tv"}) {
    Pose3 parked = ws.state().fixtures.at(fixture);
    parked.position.z() -= 3.0;
    ASSERT_EQ(ws.setFixturePose(fixture, parked), StateStatus::Ok) << fixture;
  }
  ASSERT_EQ(gRenderer->render(ws, cam, w, h, alone), RenderStatus::Ok);
  auto pixel = [&](const Image& img, int x, int y) {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * w + x);
    return std::array<int, 3>{img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]};
  };
  int black = 0, plateWhite = 0, changedTop = 0, changedBottom = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto a = pixel(company, x, y), b = pixel(alone, x, y);
      if (a[0] < 8 && a[1] < 8 && a[2] < 8 && b[0] < 8 && b[1] < 8 && b[2] < 8) ++black;
      if (y > h / 2 && a[0] > 200 && a[1] > 200 && a[2] > 200) ++plateWhite;
      if (a != b) ++(y < h / 2 ? changedTop : changedBottom);
    }
  }
  EXPECT_LT(black, w * h / 100) << "background showing: the room should fill the view";
  EXPECT_GT(plateWhite, w * h / 50) << "the white plate should fill part of the lower half";
  EXPECT_GT(changedTop, w * h / 20) << "the friend and the TV should be seen across the table";
  EXPECT_LT(changedBottom, changedTop) << "the company sits across the table, not on it";
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
