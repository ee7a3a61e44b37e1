// The Select tool's rest-pose drag (app/editor/rig_drag): the dragged point lands where the cursor's
// ray meets the plane through it that faces the camera (checked by projecting it back to the cursor's
// pixel and by its depth along the view), one undo step per drag; bones do not drag.
#include <catch2/catch.hpp>

#include "app/editor/rig_drag.h"
#include "tests/volume_test_meshes.h"

using namespace dfm;

namespace {

view::Camera test_camera(bool ortho) {
  view::Camera c;
  c.target = Eigen::Vector3d(0.1, 0.2, 0.0);
  c.distance = 4.0;
  c.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 0.5).normalized()));
  c.orthographic = ortho;
  c.width = 800, c.height = 600;
  return c;
}

}  // namespace

TEST_CASE("rig drag: a point follows the cursor on its view plane; the drag is one undo step", "[editor]") {
  for (bool ortho : {false, true}) {
    INFO("orthographic " << ortho);
    Document doc;
    doc.set_surface(test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1), "sphere");
    const Eigen::Vector3d p(0.3, -0.2, 0.4);
    const int h = doc.add_point(p);
    const view::Camera cam = test_camera(ortho);
    const int steps = doc.undo_depth();

    editor::RigDrag drag;
    drag.start_handle(doc, h, p);
    REQUIRE(drag.dragging());
    const Eigen::Vector3d px0 = view::project_to_pixel(cam, p);
    drag.update(doc, cam, px0.head<2>(), false);  // the cursor where the point is: it stays
    CHECK((doc.rig().points[0].position - p).norm() < 1e-9);
    const Eigen::Vector2d mid(px0.x() + 40, px0.y() - 25), end(px0.x() + 90, px0.y() + 30);
    drag.update(doc, cam, mid, false);
    drag.update(doc, cam, end, true);
    CHECK_FALSE(drag.dragging());

    const Eigen::Vector3d q = doc.rig().points[0].position;
    const Eigen::Vector3d px = view::project_to_pixel(cam, q);
    CHECK(std::abs(px.x() - end.x()) < 1e-6);
    CHECK(std::abs(px.y() - end.y()) < 1e-6);
    const Eigen::Vector3d f = view::camera_forward(cam);
    CHECK(std::abs((q - p).dot(f)) < 1e-9);  // same depth: the plane faces the camera
    CHECK(doc.undo_depth() == steps + 1);
    doc.undo();
    CHECK((doc.rig().points[0].position - p).norm() == 0);
  }
}

TEST_CASE("rig drag: a bone handle does not drag; cancel closes the step", "[editor]") {
  Document doc;
  doc.set_surface(test::icosphere(Eigen::Vector3d::Zero(), 1.0, 1), "sphere");
  doc.add_bone_chain({Eigen::Vector3d(0, -0.5, 0), Eigen::Vector3d(0, 0.5, 0)});
  editor::RigDrag drag;
  drag.start_handle(doc, 0, Eigen::Vector3d(0, -0.5, 0));
  CHECK_FALSE(drag.dragging());
  const int h = doc.add_point(Eigen::Vector3d(0.2, 0, 0));
  const int steps = doc.undo_depth();
  drag.start_handle(doc, h, Eigen::Vector3d(0.2, 0, 0));
  CHECK(drag.dragging());
  drag.cancel(doc);
  CHECK_FALSE(drag.dragging());
  CHECK(doc.undo_depth() == steps);  // nothing moved: no step
}
