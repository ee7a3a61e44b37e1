// The candy wrapper (Jacobson 2013, Fig. 6.1 and 6.2): arm.obj bound to arm.tgf, the wrist turned half
// a turn. Turning the hand bone with LBS collapses the wrist; twisting the forearm by 180 degrees at its
// end with STBS keeps the wrist's radius and the arm's volume and spreads the twist along the forearm.
// Measured here against the rest mesh: distances to the forearm's axis, the enclosed volume, angles
// about the axis (issue 33's acceptance).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/anim/surface_checks.h"
#include "core/scene/script.h"
#include "tests/test_support.h"

using namespace dfm;

namespace {

void run(Document& d, const std::string& text) { run_script(d, parse_script(text, "arm.txt"), "arm.txt"); }

struct Axis {
  Eigen::RowVector3d a, dir;  // through the forearm's joints
  double length = 0;
  Eigen::RowVector3d radial(const Eigen::RowVector3d& p) const { return (p - a) - (p - a).dot(dir) * dir; }
  double along(const Eigen::RowVector3d& p) const { return (p - a).dot(dir) / length; }
};

// The signed angle from u to v about dir (both radial), in degrees.
double angle_about(const Eigen::RowVector3d& u, const Eigen::RowVector3d& v, const Eigen::RowVector3d& dir) {
  return std::atan2(u.cross(v).dot(dir), u.dot(v)) * 180 / M_PI;
}

}  // namespace

TEST_CASE("candy wrapper: LBS collapses a turned wrist; STBS with the forearm twisted keeps it and spreads the twist",
          "[skin][stbs][data]") {
  DFM_DATA_OR_SKIP(mesh, "arm.obj");
  DFM_DATA_OR_SKIP(tgf, "arm.tgf");
  Document d;
  run(d, "open " + mesh + "\nload-skeleton " + tgf + "\nbind\n");
  REQUIRE(d.rig().skeleton.num_bones() == 4);
  const int forearm = 2, hand = 3;  // joints 3 -> 4 and 4 -> 5 of the TGF
  const Eigen::MatrixXd& J = d.rig().skeleton.joints;
  Axis ax;
  ax.a = J.row(d.rig().skeleton.bones[forearm].a);
  ax.dir = J.row(d.rig().skeleton.bones[forearm].b) - ax.a;
  ax.length = ax.dir.norm();
  ax.dir /= ax.length;
  const TriMesh rest = d.surface();
  const double rest_volume = enclosed_volume(rest.V, rest.F);
  const Eigen::MatrixXd& W = d.weights();
  std::vector<int> wrist;  // half on the forearm, half on the hand
  for (int i = 0; i < W.rows(); ++i)
    if (W(i, forearm) + W(i, hand) > 0.9 && std::abs(W(i, forearm) - W(i, hand)) < 0.2) wrist.push_back(i);
  REQUIRE(wrist.size() >= 20);
  auto kept_radius = [&](const Eigen::MatrixXd& V) {
    double sum = 0;
    for (int i : wrist) sum += ax.radial(V.row(i)).norm() / ax.radial(rest.V.row(i)).norm();
    return sum / static_cast<double>(wrist.size());
  };

  // LBS: the hand bone turned half a turn about the forearm's axis.
  const std::string axis = std::to_string(ax.dir.x()) + " " + std::to_string(ax.dir.y()) + " " + std::to_string(ax.dir.z());
  run(d, "set-method lbs\nselect " + std::to_string(hand) + "\nrotate 180 " + axis + "\n");
  const TriMesh lbs = posed_surface(d);
  const double lbs_kept = kept_radius(lbs.V), lbs_volume = enclosed_volume(lbs.V, lbs.F) / rest_volume;
  WARN("LBS, hand turned 180 degrees: the wrist's " << wrist.size() << " vertices keep " << lbs_kept
                                                   << " of their distance to the forearm's axis; volume " << lbs_volume << " of the rest");
  CHECK(lbs_kept < 0.5);

  // STBS: the forearm twisted by 180 degrees at its end; the hand follows.
  run(d, "reset-pose\nset-method stbs\ntwist " + std::to_string(forearm) + " 180\n");
  const TriMesh stbs = posed_surface(d);
  const double stbs_kept = kept_radius(stbs.V), stbs_volume = enclosed_volume(stbs.V, stbs.F) / rest_volume;
  WARN("STBS, forearm twisted 180 degrees: the wrist keeps " << stbs_kept << " of its distance; volume " << stbs_volume);
  CHECK(stbs_kept >= 0.9);
  CHECK(std::abs(stbs_volume - 1) <= 0.02);
  // Spread along the forearm: on its own vertices, the turn about the axis grows from its start to its end.
  double turn[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  for (int i = 0; i < W.rows(); ++i) {
    const double s = ax.along(rest.V.row(i));
    if (W(i, forearm) < 0.95 || s < 0.1 || s > 0.9) continue;
    const int third = std::min(2, static_cast<int>((s - 0.1) / 0.8 * 3));
    turn[third] += std::abs(angle_about(ax.radial(rest.V.row(i)), ax.radial(stbs.V.row(i)), ax.dir));
    ++count[third];
  }
  for (int k = 0; k < 3; ++k) {
    REQUIRE(count[k] > 0);
    turn[k] /= count[k];
  }
  WARN("STBS: mean turn about the forearm's axis over its thirds " << turn[0] << ", " << turn[1] << ", " << turn[2] << " degrees");
  CHECK(turn[0] < turn[1]);
  CHECK(turn[1] < turn[2]);
  CHECK(turn[0] < 90);
  CHECK(turn[2] > 90);

  // STBS over DQS (6.2.1, Fig. 6.7): at rest twist it is DQS bit for bit; twisted, a vertex on the
  // forearm alone moves as STBS over LBS moves it; with the elbow bent too it keeps more of the arm's
  // volume than STBS over LBS.
  run(d, "reset-pose\nselect " + std::to_string(forearm) + "\nrotate 100 0 0 1\nset-method dqs\n");
  const TriMesh dqs_bent = posed_surface(d);
  run(d, "set-method stbs-dqs\n");
  CHECK(posed_surface(d).V == dqs_bent.V);
  run(d, "twist " + std::to_string(forearm) + " 180\n");
  const TriMesh over_dqs = posed_surface(d);
  run(d, "set-method stbs\n");
  const TriMesh over_lbs = posed_surface(d);
  double single = 0;
  int on_forearm = 0;
  for (int i = 0; i < W.rows(); ++i)
    if (W(i, forearm) == 1.0) single = std::max(single, (over_dqs.V.row(i) - over_lbs.V.row(i)).norm()), ++on_forearm;
  REQUIRE(on_forearm > 10);
  CHECK(single < 1e-12);
  const double v_dqs = enclosed_volume(over_dqs.V, over_dqs.F) / rest_volume;
  const double v_lbs = enclosed_volume(over_lbs.V, over_lbs.F) / rest_volume;
  WARN("elbow bent 100 degrees, forearm twisted 180: volume " << v_lbs << " of the rest over LBS, " << v_dqs << " over DQS");
  CHECK(std::abs(v_dqs - 1) < std::abs(v_lbs - 1));
}
