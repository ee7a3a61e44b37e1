#include "core/scene/script_weights.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/util/error.h"

namespace dfm::script_detail {
namespace {

double number(const std::string& w) {
  char* end = nullptr;
  const double x = std::strtod(w.c_str(), &end);
  if (end == w.c_str() || *end != '\0' || !std::isfinite(x)) throw Error("'" + w + "' is not a finite number");
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
std::vector<int> handles(const ScriptLine& l, size_t from, const Rig* rig = nullptr) {
  std::vector<int> h;
  for (size_t i = from; i < l.words.size(); ++i) {
    char* end = nullptr;
    std::strtod(l.words[i].c_str(), &end);
    const bool numeric = end != l.words[i].c_str() && *end == '\0';
    if (rig) h.push_back(find_handle(*rig, l.words[i]));
    else if (numeric) integer(l.words[i], 0, 1000000000, "handle");
  }
  return h;
}

LimitOptions limit_options(const ScriptLine& l) {
  LimitOptions o;
  o.k = integer(l.words[1], 1, 1000000, "influence count");
  if (l.words.size() > 2) o.radius = number(l.words[2]);
  if (o.radius < 0) throw Error("radius must be >= 0");
  return o;
}

SmoothOptions smooth_options(const ScriptLine& l) {
  SmoothOptions o;
  if (l.words.size() > 1) o.iterations = integer(l.words[1], 0, 1000, "iteration count");
  if (l.words.size() > 2) o.factor = number(l.words[2]);
  if (!(o.factor > 0 && o.factor <= 1)) throw Error("factor must be in (0, 1], got " + l.words[2]);
  if (l.words.size() > 3) {
    if (l.words[3] != "uniform" && l.words[3] != "cotan") throw Error("expected uniform or cotan, got '" + l.words[3] + "'");
    o.cotangent = l.words[3] == "cotan";
  }
  return o;
}

MirrorOptions mirror_options(const ScriptLine& l) {
  MirrorOptions o;
  const std::string& a = l.words[1];
  if (a != "x" && a != "y" && a != "z") throw Error("mirror axis must be x, y or z, got '" + a + "'");
  o.normal = Eigen::Vector3d::Unit(a[0] - 'x');
  if (l.words.size() > 2) o.offset = number(l.words[2]);
  if (l.words.size() > 3) {
    const std::string& m = l.words[3];
    if (m == "+") o.mode = MirrorMode::PositiveToNegative;
    else if (m == "-") o.mode = MirrorMode::NegativeToPositive;
    else if (m == "flip") o.mode = MirrorMode::Flip;
    else throw Error("mirror mode must be +, - or flip, got '" + m + "'");
  }
  if (l.words.size() > 4) o.tolerance = number(l.words[4]);
  if (o.tolerance < 0) throw Error("tolerance must be >= 0");
  return o;
}

double report_threshold(const ScriptLine& l) { return l.words.size() > 1 ? number(l.words[1]) : 1e-3; }

}  // namespace

void check_weight_command(const ScriptLine& l) {
  const std::string& c = l.words[0];
  if (c == "weights-limit") limit_options(l);
  else if (c == "weights-normalize") handles(l, 1);
  else if (c == "weights-smooth") smooth_options(l), handles(l, 4);
  else if (c == "weights-mirror") mirror_options(l);
  else if (c == "weights-report") report_threshold(l);
}

bool run_weight_command(Document& doc, const ScriptLine& l, const std::function<void(const std::string&)>& print) {
  const std::string& c = l.words[0];
  std::ostringstream out;
  if (c == "weights-limit") {
    const LimitOptions o = limit_options(l);
    const LimitReport r = doc.weights_limit(o);
    out << c << ": " << r.rows_limited << " vertices limited to " << o.k << " influences";
    if (r.fixed_rows_over_k) out << "; " << r.fixed_rows_over_k << " handle vertices keep more (bind constraints)";
  } else if (c == "weights-normalize") {
    const NormalizeReport r = doc.weights_normalize(handles(l, 1, &doc.rig()));
    out << c << ": " << r.rows_scaled << " vertices rescaled";
    if (r.rows_locked_over_one) out << "; " << r.rows_locked_over_one << " with locked weights over 1";
    if (r.rows_without_free_weight) out << "; " << r.rows_without_free_weight << " with no unlocked weight";
  } else if (c == "weights-smooth") {
    const SmoothOptions o = smooth_options(l);
    doc.weights_smooth(o, handles(l, 4, &doc.rig()));
    out << c << ": " << o.iterations << " iterations, factor " << o.factor << (o.cotangent ? ", cotangent" : ", uniform");
  } else if (c == "weights-mirror") {
    const MirrorReport r = doc.weights_mirror(mirror_options(l));
    out << c << ": " << r.vertices_changed << " vertices changed, " << r.vertices_unmatched
        << " without a mirror within the tolerance";
    for (int h : r.unmatched_handles) out << "; no mirror handle for " << handle_name(doc.rig(), h);
  } else if (c == "weights-report") {
    if (!doc.has_weights()) throw Error("needs weights: " + doc.weights_note() + " (bind first)");
    const double t = report_threshold(l);
    const auto r = doc.weights_report(t);
    out << c << ": " << r.size() << " of " << doc.num_handles() << " handles have no weight of " << t << " or more";
    for (const ZeroWeightHandle& z : r) out << "\n  handle " << z.handle << " " << z.name << ": max " << z.max_weight;
  } else {
    return false;
  }
  if (print) print(out.str());
  return true;
}

}  // namespace dfm::script_detail
