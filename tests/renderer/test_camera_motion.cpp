// Camera animation for sequences (ActiveTransform/TransformTimes, CameraDesc::at_time) and
// the motion layer: checked against poses and screen shifts worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer_test_support.h"
#include "statmc/render/camera.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_error.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;
using statmc::render::test::quad;

namespace {

constexpr double kPi = 3.14159265358979323846;

void expect_near(const Transform& a, const Transform& b, double tolerance)
{
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(a.m[r][c], b.m[r][c], tolerance) << "element " << r << "," << c;
}

CameraDesc orbiting_camera(double degrees)
{
    CameraDesc c;
    c.world_to_camera = *Transform::look_at({0, 1, 6}, {0, 1, 0}, {0, 1, 0});
    c.world_to_camera_end = c.world_to_camera * Transform::rotate(degrees, {0, 1, 0});
    c.start_time = 0;
    c.end_time = 2;
    return c;
}

// pbrt-v3's interpolation too: the orientation turns at a constant rate, the position moves
// along the chord between the two (not along the orbit's arc).
Transform expected_pose(const CameraDesc& c, double degrees, double s)
{
    const Transform orbit = *(c.world_to_camera * Transform::rotate(degrees, {0, 1, 0})).inverse();
    const Transform start = *c.world_to_camera.inverse(), end = *c.world_to_camera_end.inverse();
    Transform pose = orbit;
    for (int r = 0; r < 3; ++r)
        pose.m[r][3] = start.m[r][3] + s * (end.m[r][3] - start.m[r][3]);
    return *pose.inverse();
}

TEST(CameraMotion, AtTimeTurnsAtAConstantRate)
{
    const CameraDesc c = orbiting_camera(20);
    ASSERT_TRUE(c.animated());
    ASSERT_TRUE(camera_motion_is_rigid(c));
    expect_near(c.at_time(0).world_to_camera, c.world_to_camera, 1e-9);
    expect_near(c.at_time(2).world_to_camera, c.world_to_camera_end, 1e-9);
    expect_near(c.at_time(-1).world_to_camera, c.world_to_camera, 1e-9);  // held
    expect_near(c.at_time(5).world_to_camera, c.world_to_camera_end, 1e-9);
    expect_near(c.at_time(0.5).world_to_camera, expected_pose(c, 5, 0.25), 1e-9);
    expect_near(c.at_time(1).world_to_camera, expected_pose(c, 10, 0.5), 1e-9);
}

TEST(CameraMotion, ADollyMovesLinearly)
{
    CameraDesc c;
    c.world_to_camera = *Transform::look_at({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    c.world_to_camera_end = *Transform::look_at({0, 0, 4}, {0, 0, -6}, {0, 1, 0});
    expect_near(c.at_time(0.25).world_to_camera,
                *Transform::look_at({0, 0, 8.5}, {0, 0, -1.5}, {0, 1, 0}), 1e-9);
}

TEST(CameraMotion, ScalingIsNotACameraMotion)
{
    CameraDesc c;
    c.world_to_camera = *Transform::look_at({0, 0, 10}, {0, 0, 0}, {0, 1, 0});
    c.world_to_camera_end = c.world_to_camera * Transform::scale({2, 2, 2});
    EXPECT_FALSE(camera_motion_is_rigid(c));
    EXPECT_THROW(c.at_time(0.5), SceneError);
}

TEST(CameraMotion, RasterInvertsGenerate)
{
    const CameraDesc c = orbiting_camera(20).at_time(0.7);
    const Camera camera(c, 64, 48);
    for (float x : {0.5f, 13.25f, 63.5f})
        for (float y : {0.5f, 30.75f, 47.5f}) {
            const Ray ray = camera.generate(x, y);
            float rx = 0, ry = 0;
            ASSERT_TRUE(camera.raster(ray.origin + ray.direction * 3.f, rx, ry));
            EXPECT_NEAR(rx, x, 1e-3);
            EXPECT_NEAR(ry, y, 1e-3);
        }
    const Ray ray = camera.generate(10, 10);
    float rx = 0, ry = 0;
    EXPECT_FALSE(camera.raster(ray.origin - ray.direction * 3.f, rx, ry));  // behind it
}

TEST(CameraMotion, ParserReadsActiveTransformAndTransformTimes)
{
    const std::string head = "TransformTimes 0 2\n"
                             "ActiveTransform StartTime\nLookAt 0 0 10  0 0 0  0 1 0\n"
                             "ActiveTransform EndTime\nLookAt 2 0 10  2 0 0  0 1 0\n"
                             "ActiveTransform All\n"
                             "Camera \"perspective\" \"float fov\" 40\nWorldBegin\nWorldEnd\n";
    const SceneDescription desc = parse_scene_string(head, "t.pbrt");
    EXPECT_TRUE(desc.camera.animated());
    EXPECT_EQ(desc.camera.end_time, 2);
    expect_near(desc.camera.world_to_camera, *Transform::look_at({0, 0, 10}, {0, 0, 0}, {0, 1, 0}),
                1e-12);
    expect_near(desc.camera.world_to_camera_end,
                *Transform::look_at({2, 0, 10}, {2, 0, 0}, {0, 1, 0}), 1e-12);

    auto error_of = [](const std::string& text) {
        try {
            parse_scene_string(text, "t.pbrt");
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    EXPECT_NE(error_of("ActiveTransform Sometimes\n").find("expected StartTime, EndTime or All"),
              std::string::npos);
    EXPECT_NE(error_of("TransformTimes 1 0\n").find("start time must be below"), std::string::npos);
    EXPECT_NE(error_of("ActiveTransform EndTime\nScale 2 2 2\nActiveTransform All\n"
                       "Camera \"perspective\"\nWorldBegin\nWorldEnd\n")
                  .find("rotation and a translation only"),
              std::string::npos);
}

TEST(CameraMotion, MotionLayerIsTheScreenShiftOfATrackingShot)
{
    // A camera sliding sideways by 0.5 per frame in front of an emitting wall at distance
    // 10: each point of the wall moves by 0.5 · (W/2) / (10 · tan(fov/2)) pixels across the
    // screen between frames, the same everywhere, and not at all vertically.
    const int w = 32, h = 32;
    const double fov = 40, step = 0.5, distance = 10;
    const std::string text = "TransformTimes 0 1\n"
                             "ActiveTransform StartTime\nLookAt 0 0 10  0 0 0  0 1 0\n"
                             "ActiveTransform EndTime\nLookAt 0.5 0 10  0.5 0 0  0 1 0\n"
                             "ActiveTransform All\nCamera \"perspective\" \"float fov\" 40\n"
                             "WorldBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" +
                             quad("-50 -50 0  50 -50 0  50 50 0  -50 50 0", "0 0 1") + "WorldEnd\n";
    const SceneDescription desc = parse_scene_string(text, "slide.pbrt");
    Scene scene(desc);
    const Camera camera(desc.camera.at_time(1), w, h), previous(desc.camera.at_time(0), w, h);
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.schedule = schedule_for_spp(4);
    rs.previous_camera = &previous;
    Film film(w, h);
    film.track_motion();
    render(scene, camera, rs, film);
    const std::vector<float> motion = film.motion();
    const double expected = step * (w / 2.0) / (distance * std::tan(fov / 2 * kPi / 180));
    for (int i = 0; i < w * h; ++i) {
        ASSERT_NEAR(std::abs(motion[i]), expected, 1e-3) << "pixel " << i;
        ASSERT_NEAR(motion[w * h + i], 0, 1e-3) << "pixel " << i;
        ASSERT_EQ(motion[i] > 0, motion[0] > 0);
    }
    // A film that tracks motion without the previous camera is a caller error.
    rs.previous_camera = nullptr;
    EXPECT_THROW(render(scene, camera, rs, film), std::invalid_argument);
}

}  // namespace
