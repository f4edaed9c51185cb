// The viewer's pieces that need no window: the fly camera and sun angles against the pinhole
// camera's own projection (scene::CameraFrame), the controls' state changes, the camera-path
// format, and the LUT-set and screenshot-name choices. The window itself is tested under Xvfb
// (tests/view/test_view_window.py).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/Errors.h"
#include "scene/CameraPath.h"
#include "support/CliRunner.h"
#include "support/RenderLuts.h"
#include "support/TempDir.h"
#include "view/FlyCamera.h"
#include "view/Viewer.h"
#include "view/ViewerControls.h"

using namespace cloudlut;
using Catch::Matchers::Contains;

namespace {

// Pixel column of a world point in a w × h image of `camera`, from CameraFrame's ray directions
// (the column whose ray has the point's horizontal angle; bisection).
float projectedColumn(const scene::Camera& camera, const glm::vec3& point, int w, int h) {
  const scene::CameraFrame frame(camera, w, h);
  const glm::vec3 toPoint = glm::normalize(point - camera.eye);
  const glm::vec3 right = glm::normalize(glm::cross(frame.forward(), camera.up));
  float lo = -10.0f * static_cast<float>(w), hi = 11.0f * static_cast<float>(w);
  for (int i = 0; i < 80; ++i) {
    const float mid = 0.5f * (lo + hi);
    const float side = glm::dot(frame.rayDirection(mid, 0.5f * static_cast<float>(h)), right) /
                           glm::dot(frame.rayDirection(mid, 0.5f * static_cast<float>(h)), frame.forward()) -
                       glm::dot(toPoint, right) / glm::dot(toPoint, frame.forward());
    (side < 0.0f ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

}  // namespace

TEST_CASE("view: fly camera angles reproduce a look-at camera, and turning left moves the picture right", "[view]") {
  scene::Camera look;
  look.eye = {100.0f, 600.0f, 50.0f};
  look.target = {-400.0f, 900.0f, -5000.0f};
  look.fovDeg = 50.0f;
  const view::FlyCamera fly = view::FlyCamera::fromCamera(look);
  const glm::vec3 expected = glm::normalize(look.target - look.eye);
  CHECK(glm::length(fly.forward() - expected) < 1e-5f);
  CHECK(std::abs(glm::dot(fly.right(), fly.forward())) < 1e-5f);
  CHECK(glm::dot(glm::cross(fly.right(), fly.forward()), glm::vec3(0, 1, 0)) > 0.0f);  // right-handed, +y up

  // A point straight ahead at the centre column; after a left turn of d degrees it lies
  // f·tan(d) pixels to the right of the centre, f = (h/2)/tan(fov/2).
  const int w = 320, h = 180;
  const glm::vec3 ahead = look.eye + 3000.0f * fly.forward();
  CHECK(projectedColumn(fly.camera(), ahead, w, h) == Approx(160.0f).margin(0.01));
  view::FlyCamera turned = fly;
  turned.turn(5.0f, 0.0f);
  const float f = 90.0f / std::tan(glm::radians(25.0f));
  const float shift = projectedColumn(turned.camera(), ahead, w, h) - 160.0f;
  CHECK(shift == Approx(f * std::tan(glm::radians(5.0f))).epsilon(0.02));
}

TEST_CASE("view: sun angles and direction agree both ways", "[view]") {
  for (const glm::vec3 d : {glm::vec3(0.4f, 0.8f, 0.45f), glm::vec3(-0.3f, 0.2f, -0.9f), glm::vec3(0.0f, -1.0f, 0.001f)}) {
    const view::SunAngles s = view::SunAngles::fromDirection(d);
    CHECK(glm::length(s.direction() - glm::normalize(d)) < 1e-4f);
  }
  view::SunAngles s;
  s.turn(0.0f, 80.0f);
  CHECK(s.elevationDeg == 90.0f);  // clamped
}

TEST_CASE("view: controls change the state the loop renders", "[view]") {
  view::ViewerState s;
  s.lutSetCount = 2;
  const float yaw = s.camera.yawDeg;
  view::onKey(s, GLFW_KEY_LEFT, GLFW_PRESS, 0);
  view::onKey(s, GLFW_KEY_LEFT, GLFW_REPEAT, 0);
  CHECK(s.camera.yawDeg == Approx(yaw + 2 * view::kTurnStepDeg));
  view::onKey(s, GLFW_KEY_LEFT, GLFW_RELEASE, 0);
  CHECK(s.camera.yawDeg == Approx(yaw + 2 * view::kTurnStepDeg));
  view::onKey(s, GLFW_KEY_B, GLFW_PRESS, 0);
  CHECK(s.blend == render::BlendMode::Alpha);
  view::onKey(s, GLFW_KEY_B, GLFW_REPEAT, 0);  // switches act once per press
  CHECK(s.blend == render::BlendMode::Alpha);
  view::onKey(s, GLFW_KEY_X, GLFW_PRESS, 0);
  CHECK(s.terms == (render::kTermSingle | render::kTermAmbient));
  view::onKey(s, GLFW_KEY_3, GLFW_PRESS, 0);
  CHECK(s.quality == 2);
  view::onKey(s, GLFW_KEY_N, GLFW_PRESS, 0);
  view::onKey(s, GLFW_KEY_N, GLFW_PRESS, 0);
  CHECK(s.lutSet == 0);  // cycles
  view::onKey(s, GLFW_KEY_M, GLFW_PRESS, 0);  // seed lighting takes the seed's sunlight
  CHECK(s.lighting == render::LightingModel::Seed);
  CHECK(s.sunlight == render::SunlightModel::Particle);
  view::onKey(s, GLFW_KEY_P, GLFW_PRESS, 0);
  CHECK(s.sunlight == render::SunlightModel::Volume);
  view::onKey(s, GLFW_KEY_M, GLFW_PRESS, 0);
  CHECK(s.lighting == render::LightingModel::Cloud);
  CHECK(s.sunlight == render::SunlightModel::Volume);
  view::onKey(s, GLFW_KEY_F, GLFW_PRESS, 0);
  CHECK_FALSE(s.diffusion);
  view::onKey(s, GLFW_KEY_F12, GLFW_PRESS, 0);
  CHECK(s.screenshots == 1);
  CHECK_FALSE(s.quit);
  view::onKey(s, GLFW_KEY_ESCAPE, GLFW_PRESS, 0);
  CHECK(s.quit);

  view::onScroll(s, 2.0);
  CHECK(s.speed == Approx(300.0f * 1.25f * 1.25f));
  view::onScroll(s, -1000.0);
  CHECK(s.speed == 1.0f);

  // W tapped for 0.2 s within a long frame, E held from 1.0 s on: at 2.0 s the camera has moved
  // 0.2·speed forward and 1.0·speed up; E still held, the next 0.5 s move it 0.5·speed up.
  s.speed = 300.0f;
  const glm::vec3 eye = s.camera.eye, forward = s.camera.forward();
  view::MotionKeys motion;
  motion.onKey(GLFW_KEY_W, GLFW_PRESS, 0.3);
  motion.onKey(GLFW_KEY_W, GLFW_REPEAT, 0.4);
  motion.onKey(GLFW_KEY_W, GLFW_RELEASE, 0.5);
  motion.onKey(GLFW_KEY_E, GLFW_PRESS, 1.0);
  motion.onKey(GLFW_KEY_LEFT, GLFW_PRESS, 1.0);  // not a motion key
  view::advance(s, motion.take(2.0));
  CHECK(glm::length(s.camera.eye - (eye + 60.0f * forward + glm::vec3(0, 300, 0))) < 1e-2f);
  const view::HeldSeconds next = motion.take(2.5);
  CHECK(next.up == Approx(0.5));
  CHECK(next.forward == 0.0);
  motion.onKey(GLFW_KEY_E, GLFW_RELEASE, 2.7);
  CHECK(motion.take(3.0).up == Approx(0.2));
  CHECK(motion.take(4.0).up == 0.0);
  motion.onKey(GLFW_KEY_A, GLFW_PRESS, 4.5);  // a tap polled as one instant
  motion.onKey(GLFW_KEY_A, GLFW_RELEASE, 4.5);
  CHECK(motion.take(5.0).left == Approx(view::kTapSeconds));

  const float pitch = s.camera.pitchDeg;
  view::onDrag(s, 0.0, -10.0, false);  // drag up: look up
  CHECK(s.camera.pitchDeg == Approx(pitch + 10.0f * view::kDragDegPerPixel));
}

TEST_CASE("view: camera paths round-trip through JSON and bad ones name the field", "[view]") {
  scene::CameraPath path;
  for (int i = 0; i < 3; ++i) {
    scene::CameraPathFrame f;
    f.seconds = 0.25 * i;
    f.camera.eye = {10.0f * static_cast<float>(i), 600.0f, -3.5f};
    f.camera.target = f.camera.eye + glm::vec3(0.0f, 0.1f, -1.0f);
    f.camera.fovDeg = 40.0f + static_cast<float>(i);
    f.sunDirection = glm::normalize(glm::vec3(0.3f, 0.9f, 0.1f * static_cast<float>(i)));
    path.frames.push_back(f);
  }
  const scene::CameraPath back = scene::parseCameraPath(nlohmann::json::parse(scene::cameraPathText(path)), "p");
  REQUIRE(back.frames.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CHECK(back.frames[i].seconds == path.frames[i].seconds);
    CHECK(back.frames[i].camera.eye == path.frames[i].camera.eye);
    CHECK(back.frames[i].camera.target == path.frames[i].camera.target);
    CHECK(back.frames[i].camera.fovDeg == path.frames[i].camera.fovDeg);
    CHECK(glm::length(back.frames[i].sunDirection - path.frames[i].sunDirection) < 1e-6f);
  }

  const auto fails = [&](const std::function<void(nlohmann::json&)>& edit, const std::string& message) {
    nlohmann::json j = scene::cameraPathToJson(path);
    edit(j);
    CHECK_THROWS_WITH(scene::parseCameraPath(j, "flight.json"), Contains(message));
  };
  fails([](nlohmann::json& j) { j["frames"][1]["eye"] = {1, 2}; }, "flight.json: frames[1].eye: expected 3 numbers");
  fails([](nlohmann::json& j) { j["frames"][2]["seconds"] = 0.1; }, "frames[2].seconds: earlier than the frame before it");
  fails([](nlohmann::json& j) { j["frames"][0]["target"] = j["frames"][0]["eye"]; }, "frames[0].target: equals the eye");
  fails([](nlohmann::json& j) { j["frames"][0]["fov_deg"] = 180; }, "frames[0].fov_deg");
  fails([](nlohmann::json& j) { j["frames"][0]["sun"] = {0, 0, 0}; }, "frames[0].sun");
  fails([](nlohmann::json& j) { j["frames"][0]["eyes"] = 1; }, "frames[0].eyes: unknown field");
  fails([](nlohmann::json& j) { j["frames"] = nlohmann::json::array(); }, "frames: expected an array of at least one frame");
  fails([](nlohmann::json& j) { j["version"] = 2; }, "version: expected 1");
  CHECK_THROWS_WITH(scene::readCameraPath("/nonexistent/path.json"), Contains("/nonexistent/path.json"));
}

TEST_CASE("view: LUT sets are found in a directory or its subdirectories, and screenshots never overwrite", "[view]") {
  test::TempDir dir;
  CHECK_THROWS_AS(view::findLutSets(dir.path()), FileError);
  for (const char* name : {"orders18", "converged", "notes"}) std::filesystem::create_directory(dir / name);
  std::ofstream(dir / "orders18" / "manifest.json") << "{}";
  std::ofstream(dir / "converged" / "manifest.json") << "{}";
  const std::vector<std::filesystem::path> sets = view::findLutSets(dir.path());
  REQUIRE(sets.size() == 2);
  CHECK(sets[0].filename() == "converged");
  CHECK(sets[1].filename() == "orders18");
  CHECK(view::findLutSets(dir / "orders18").size() == 1);

  std::ofstream(dir / "cloudlut_0000.png") << "x";
  std::ofstream(dir / "cloudlut_0001.png") << "x";
  int next = 0;
  CHECK(view::nextScreenshotPath(dir.path(), next).filename() == "cloudlut_0002.png");
  CHECK(next == 2);
}

TEST_CASE("render --path: each frame of a camera path is the render of its camera, and bad paths are refused",
          "[view][cli]") {
  test::TempDir tmp;
  test::writeSyntheticLutSet(tmp / "luts");
  scene::CameraPath path;
  for (int i = 0; i < 2; ++i) {
    scene::CameraPathFrame f;
    f.seconds = 0.5 * i;
    f.camera.eye = {0.0f, 600.0f, -200.0f * static_cast<float>(i)};
    f.camera.target = f.camera.eye + glm::vec3(0.3f * static_cast<float>(i), 0.15f, -1.0f);
    f.camera.fovDeg = 60.0f;
    f.sunDirection = glm::normalize(glm::vec3(0.45f, 0.55f, -0.7f + 0.5f * static_cast<float>(i)));
    path.frames.push_back(f);
  }
  std::ofstream(tmp / "flight.json") << scene::cameraPathText(path);
  const std::string base = "render --luts '" + (tmp / "luts").string() + "' --width 64 --height 36 --quality low --quiet ";
  const test::CliResult r = test::runCli(base + "--path '" + (tmp / "flight.json").string() + "' --out '" +
                                         (tmp / "f.png").string() + "'");
  REQUIRE(r.exitCode == 0);
  for (int i = 0; i < 2; ++i) {
    const scene::CameraPathFrame& f = path.frames[static_cast<std::size_t>(i)];
    const auto v = [](const glm::vec3& x) {  // exact float round trip
      char text[96];
      std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", static_cast<double>(x.x), static_cast<double>(x.y),
                    static_cast<double>(x.z));
      return std::string(text);
    };
    const std::string single = (tmp / ("single" + std::to_string(i) + ".png")).string();
    REQUIRE(test::runCli(base + "--eye=" + v(f.camera.eye) + " --target=" + v(f.camera.target) + " --fov 60 --sun=" +
                         v(f.sunDirection) + " --out '" + single + "'").exitCode == 0);
    const std::string framed = test::readFile(tmp / ("f_000" + std::to_string(i) + ".png"));
    CHECK(!framed.empty());
    CHECK(framed == test::readFile(single));
  }
  CHECK(test::readFile(tmp / "f_0000.png") != test::readFile(tmp / "f_0001.png"));

  const test::CliResult tooMany = test::runCli(base + "--path '" + (tmp / "flight.json").string() + "' --frames 3 --out '" +
                                               (tmp / "g.png").string() + "'");
  CHECK(tooMany.exitCode == 2);
  CHECK_THAT(tooMany.err, Contains("the path holds 2"));
  std::ofstream(tmp / "bad.json") << R"({"format": "cloudlut camera path", "version": 1, "frames": [{"seconds": 0}]})";
  const test::CliResult bad =
      test::runCli(base + "--path '" + (tmp / "bad.json").string() + "' --out '" + (tmp / "h.png").string() + "'");
  CHECK(bad.exitCode == 1);
  CHECK_THAT(bad.err, Contains("bad.json: frames[0].eye: missing"));
  CHECK_FALSE(std::filesystem::exists(tmp / "h_0000.png"));
}
