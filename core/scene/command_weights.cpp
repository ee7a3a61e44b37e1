// The table's weights-* commands (SCRIPT.md): their arguments checked before anything runs (each
// option parser names the problem its own way) and run as the Document's weights_* commands.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/bind/weight_transfer.h"
#include "core/mesh/io.h"
#include "core/scene/command_parts.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace dfm::command_detail {
namespace {

double number(const std::string& w) {
  double x = 0;
  if (!parse_number(w, x)) throw Error("'" + w + "' is not a finite number");
  return x;
}

int integer(const std::string& w, int lo, int hi, const char* what) {
  const double x = number(w);
  if (x != std::floor(x) || x < lo || x > hi)
    throw Error(std::string(what) + " '" + w + "' must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  return static_cast<int>(x);
}

// Handle words from `from` on: at parse time (rig null) a number must be a handle number, a name
// waits for the run; at run time each is find_handle's.
std::vector<int> handles(const CommandWords& w, size_t from, const Rig* rig = nullptr) {
  std::vector<int> h;
  for (size_t i = from; i < w.size(); ++i) {
    char* end = nullptr;
    std::strtod(w[i].c_str(), &end);
    const bool numeric = end != w[i].c_str() && *end == '\0';
    if (rig) h.push_back(find_handle(*rig, w[i]));
    else if (numeric) integer(w[i], 0, 1000000000, "handle");
  }
  return h;
}

LimitOptions limit_options(const CommandWords& w) {
  LimitOptions o;
  o.k = integer(w[1], 1, 1000000, "influence count");
  if (w.size() > 2) o.radius = number(w[2]);
  if (o.radius < 0) throw Error("radius must be >= 0");
  return o;
}

SmoothOptions smooth_options(const CommandWords& w) {
  SmoothOptions o;
  if (w.size() > 1) o.iterations = integer(w[1], 0, 1000, "iteration count");
  if (w.size() > 2) o.factor = number(w[2]);
  if (!(o.factor > 0 && o.factor <= 1)) throw Error("factor must be in (0, 1], got " + w[2]);
  if (w.size() > 3) {
    if (w[3] != "uniform" && w[3] != "cotan") throw Error("expected uniform or cotan, got '" + w[3] + "'");
    o.cotangent = w[3] == "cotan";
  }
  return o;
}

MirrorOptions mirror_options(const CommandWords& w) {
  MirrorOptions o;
  const std::string& a = w[1];
  if (a != "x" && a != "y" && a != "z") throw Error("mirror axis must be x, y or z, got '" + a + "'");
  o.normal = Eigen::Vector3d::Unit(a[0] - 'x');
  if (w.size() > 2) o.offset = number(w[2]);
  if (w.size() > 3) {
    const std::string& m = w[3];
    if (m == "+") o.mode = MirrorMode::PositiveToNegative;
    else if (m == "-") o.mode = MirrorMode::NegativeToPositive;
    else if (m == "flip") o.mode = MirrorMode::Flip;
    else throw Error("mirror mode must be +, - or flip, got '" + m + "'");
  }
  if (w.size() > 4) o.tolerance = number(w[4]);
  if (o.tolerance < 0) throw Error("tolerance must be >= 0");
  return o;
}

double report_threshold(const CommandWords& w) { return w.size() > 1 ? number(w[1]) : 1e-3; }

// The line's check: the option parser's message, then the usage.
std::function<void(const CommandWords&, const std::string&)> line_check(void (*check)(const CommandWords&)) {
  return [check](const CommandWords& w, const std::string& usage) {
    try {
      check(w);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) + "; usage: " + usage);
    }
  };
}

void limit(CommandContext& x, const CommandWords& w) {
  const LimitOptions o = limit_options(w);
  const LimitReport r = x.doc.weights_limit(o);
  std::ostringstream out;
  out << w[0] << ": " << r.rows_limited << " vertices limited to " << o.k << " influences";
  if (r.fixed_rows_over_k) out << "; " << r.fixed_rows_over_k << " handle vertices keep more (bind constraints)";
  x.print(out.str());
}

void normalize(CommandContext& x, const CommandWords& w) {
  const NormalizeReport r = x.doc.weights_normalize(handles(w, 1, &x.doc.rig()));
  std::ostringstream out;
  out << w[0] << ": " << r.rows_scaled << " vertices rescaled";
  if (r.rows_locked_over_one) out << "; " << r.rows_locked_over_one << " with locked weights over 1";
  if (r.rows_without_free_weight) out << "; " << r.rows_without_free_weight << " with no unlocked weight";
  x.print(out.str());
}

void smooth(CommandContext& x, const CommandWords& w) {
  const SmoothOptions o = smooth_options(w);
  x.doc.weights_smooth(o, handles(w, 4, &x.doc.rig()));
  std::ostringstream out;
  out << w[0] << ": " << o.iterations << " iterations, factor " << o.factor << (o.cotangent ? ", cotangent" : ", uniform");
  x.print(out.str());
}

void mirror(CommandContext& x, const CommandWords& w) {
  const MirrorReport r = x.doc.weights_mirror(mirror_options(w));
  std::ostringstream out;
  out << w[0] << ": " << r.vertices_changed << " vertices changed, " << r.vertices_unmatched
      << " without a mirror within the tolerance";
  for (int h : r.unmatched_handles) out << "; no mirror handle for " << handle_name(x.doc.rig(), h);
  x.print(out.str());
}

void report(CommandContext& x, const CommandWords& w) {
  if (!x.doc.has_weights()) throw Error("needs weights: " + x.doc.weights_note() + " (bind first)");
  const double t = report_threshold(w);
  const auto r = x.doc.weights_report(t);
  std::ostringstream out;
  out << w[0] << ": " << r.size() << " of " << x.doc.num_handles() << " handles have no weight of " << t << " or more";
  for (const ZeroWeightHandle& z : r) out << "\n  handle " << z.handle << " " << z.name << ": max " << z.max_weight;
  x.print(out.str());
}

// A bound scene's surface and weights, or a mesh and its weights file, carried onto the document's
// surface (core/bind/weight_transfer.h); the handles correspond by number.
void transfer(CommandContext& x, const CommandWords& w) {
  TriMesh source;
  Eigen::MatrixXd W;
  if (file_extension(w[1]) == "json") {
    Document from;
    from.load_scene(w[1]);
    if (!from.has_weights()) throw Error(w[1] + ": the scene has no weights to transfer (" + from.weights_note() + ")");
    source = from.surface();
    W = from.weights();
  } else {
    if (w.size() < 3) throw Error("a mesh needs its weights: transfer-weights " + w[1] + " W.dmat");
    source = read_surface(w[1]);
    W = read_dmat(w[2]);
  }
  if (W.cols() != x.doc.num_handles())
    throw Error((w.size() > 2 ? w[2] : w[1]) + ": " + std::to_string(W.cols()) + " handles' weights, but the rig has " +
                std::to_string(x.doc.num_handles()) + " (handles correspond by number)");
  if (x.doc.surface().num_vertices() == 0) throw Error("no surface to transfer the weights onto (open a mesh first)");
  WeightTransferReport r;
  const Eigen::MatrixXd T = transfer_weights(source.V, source.F, W, x.doc.surface().V, x.doc.surface().F, {}, &r);
  std::ostringstream out;
  out << w[0] << ": " << r.matched << " vertices matched on " << w[1] << ", " << r.inpainted << " inpainted, " << r.nearest
      << " in pieces with no match (their closest points)";
  BindStats st;
  st.notes = {out.str()};
  x.doc.set_weights(T, st);
  x.print(out.str());
}

// paint-weights HANDLE MODE X Y Z RADIUS STRENGTH [VALUE] [falloff=F] [front=DX,DY,DZ] [mirror]
// [locked=H,H,...]: one dab of the weight brush (weight_brush.h), as the Paint tool makes it.
struct PaintWeightsLine {
  WeightBrush brush;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  bool mirror = false;
  std::vector<std::string> locked;  // handle words
};

WeightPaintMode paint_mode(const std::string& m) {
  if (m == "add") return WeightPaintMode::Add;
  if (m == "subtract") return WeightPaintMode::Subtract;
  if (m == "mix") return WeightPaintMode::Mix;
  if (m == "smooth") return WeightPaintMode::Smooth;
  throw Error("brush mode must be add, subtract, mix or smooth, got '" + m + "'");
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string part; std::getline(in, part, ',');) out.push_back(part);
  return out;
}

PaintWeightsLine paint_weights_line(const CommandWords& w) {
  PaintWeightsLine p;
  p.brush.mode = paint_mode(w[2]);
  p.center = Eigen::Vector3d(number(w[3]), number(w[4]), number(w[5]));
  p.brush.radius = number(w[6]);
  p.brush.strength = number(w[7]);
  if (!(p.brush.radius > 0)) throw Error("radius must be > 0, got " + w[6]);
  if (!(p.brush.strength >= 0 && p.brush.strength <= 1)) throw Error("strength must be in [0, 1], got " + w[7]);
  size_t i = 8;
  if (p.brush.mode == WeightPaintMode::Mix) {
    if (w.size() <= i) throw Error("mix needs the VALUE to blend toward");
    p.brush.value = number(w[i++]);
    if (!(p.brush.value >= 0 && p.brush.value <= 1)) throw Error("the mix value must be in [0, 1], got " + w[i - 1]);
  }
  for (; i < w.size(); ++i) {
    const std::string& o = w[i];
    if (o == "mirror") {
      p.mirror = true;
    } else if (o.rfind("falloff=", 0) == 0) {
      p.brush.falloff = number(o.substr(8));
      if (!(p.brush.falloff >= 0 && p.brush.falloff <= 1)) throw Error("falloff must be in [0, 1], got " + o.substr(8));
    } else if (o.rfind("front=", 0) == 0) {
      const std::vector<std::string> d = split_commas(o.substr(6));
      if (d.size() != 3) throw Error("front= takes a view direction DX,DY,DZ, got '" + o.substr(6) + "'");
      p.brush.facing = Eigen::Vector3d(number(d[0]), number(d[1]), number(d[2]));
    } else if (o.rfind("locked=", 0) == 0) {
      p.locked = split_commas(o.substr(7));
    } else {
      throw Error("unknown option '" + o + "' (falloff=F, front=DX,DY,DZ, mirror, locked=H,H)");
    }
  }
  return p;
}

void paint_weights(CommandContext& x, const CommandWords& w) {
  const PaintWeightsLine p = paint_weights_line(w);
  const int handle = find_handle(x.doc.rig(), w[1]);
  std::vector<int> locked;
  for (const std::string& h : p.locked) locked.push_back(find_handle(x.doc.rig(), h));
  const int changed = x.doc.paint_weights(handle, p.center, p.brush, locked, p.mirror);
  x.print(w[0] + ": " + std::to_string(changed) + " vertices changed");
}

}  // namespace

void add_weight_commands(std::vector<Command>& t) {
  const ArgSpec a_number = arg_checked_by_line(ArgKind::Number), a_handle = arg_checked_by_line(ArgKind::Handle);
  const ArgSpec a_word = arg_checked_by_line(ArgKind::Word);
  add(t, "weights-limit", "weights-limit K [RADIUS]", 1, 2, {a_number}, limit).check =
      line_check([](const CommandWords& w) { limit_options(w); });
  add(t, "weights-normalize", "weights-normalize [LOCKED_HANDLE ...]", 0, 1000, {a_handle}, normalize).check =
      line_check([](const CommandWords& w) { handles(w, 1); });
  add(t, "weights-smooth", "weights-smooth [N [FACTOR [uniform|cotan [LOCKED_HANDLE ...]]]]", 0, 1000,
      {a_number, a_number, a_word, a_handle}, smooth)
      .check = line_check([](const CommandWords& w) { smooth_options(w), handles(w, 4); });
  add(t, "weights-mirror", "weights-mirror x|y|z [OFFSET [+|-|flip [TOLERANCE]]]", 1, 4, {a_word, a_number, a_word, a_number}, mirror)
      .check = line_check([](const CommandWords& w) { mirror_options(w); });
  add(t, "weights-report", "weights-report [THRESHOLD]", 0, 1, {a_number}, report).check =
      line_check([](const CommandWords& w) { report_threshold(w); });
  add(t, "transfer-weights", "transfer-weights SCENE.json | MESH W.dmat", 1, 2, {file_arg(), file_arg()}, transfer);
  Command& paint = add(t, "paint-weights",
                       "paint-weights HANDLE add|subtract|mix|smooth X Y Z RADIUS STRENGTH [VALUE] [falloff=F] "
                       "[front=DX,DY,DZ] [mirror] [locked=H,H]",
                       7, 12, {a_handle, a_word, a_number, a_number, a_number, a_number, a_number, a_word}, paint_weights);
  paint.check = line_check([](const CommandWords& w) { paint_weights_line(w); });
  paint.poll = needs_weights;
  // Each one undo step on the weights; they need weights to work on (weights-report only reads them).
  for (Command& c : t)
    if (c.name.rfind("weights-", 0) == 0) c.poll = needs_weights, c.undoable = c.name != "weights-report";
}

}  // namespace dfm::command_detail
