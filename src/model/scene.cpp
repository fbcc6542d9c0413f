#include "ddaslope/model/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/model/input_limits.hpp"

namespace ddaslope::model {

int Scene::jointBetween(int a, int b) const {
  const auto it = pairJoints.find({std::min(a, b), std::max(a, b)});
  return it == pairJoints.end() ? defaultJoint : it->second;
}

int Scene::freeUnknowns() const {
  int free = 0;
  for (const Block& b : blocks) free += !b.fixed;
  return (settings.rigidBlocks ? 3 : 6) * free;
}

double Scene::modelHalfSize() const {
  geometry::Aabb box = geometry::boundingBox(blocks.front().vertices);
  for (const Block& b : blocks) {
    const geometry::Aabb bb = geometry::boundingBox(b.vertices);
    box.lo = box.lo.cwiseMin(bb.lo);
    box.hi = box.hi.cwiseMax(bb.hi);
  }
  return 0.5 * (box.hi - box.lo).maxCoeff();
}

/// Coordinates typed or exported to the millimetre put a vertex split off an edge up to 0.7 mm
/// from it, and leave faces that touch gaps of that size: such gaps are the file's, not the rock's.
constexpr double kRoundedCoordinateGap = 1.5e-3;

double Scene::lastLoadChange() const {
  for (const PointLoad& l : pointLoads)
    if (l.rate.squaredNorm() > 0) return std::numeric_limits<double>::infinity();
  double t = 0;
  // A record is linear between its samples and zero outside them: it stops changing at the
  // sample after its last non-zero one (at its end if that is its last). All zeros (a record
  // scaled to 0): it never acts.
  const GroundMotion& g = seismic.ground;
  for (size_t k = g.times.size(); k-- > 0;) {
    const bool acts = (k < g.horizontal.size() && g.horizontal[k] != 0) || (k < g.vertical.size() && g.vertical[k] != 0);
    if (acts) {
      t = std::max(t, g.times[std::min(k + 1, g.times.size() - 1)]);
      break;
    }
  }
  // A water level is held before its first sample and after its last: it stops changing at the
  // last sample that differs from the one before it.
  const std::vector<double>& wt = water.seriesTimes;
  const std::vector<double>& wl = water.seriesLevels;
  for (size_t k = std::min(wt.size(), wl.size()); k-- > 1;)
    if (wl[k] != wl[k - 1]) {
      t = std::max(t, wt[k]);
      break;
    }
  return t;
}

double Scene::touchingGap() const {
  const double w0 = modelHalfSize();
  if (settings.initialContactTolerance >= 0) return settings.initialContactTolerance * w0;
  return std::clamp(kRoundedCoordinateGap, 1e-6 * w0, 1e-4 * w0);
}

double Scene::stepLimit() const {
  // Shi's step limit g2·w0 scales with the model. In a kilometre slope with a 15 m wedge it
  // exceeds the wedge, and the contact search (2.5 times the limit) then pairs corners farther
  // apart than the blocks are wide: contacts metres deep appear from nowhere (the Vajont
  // run-out ejected its toe wedge so). The limit is therefore also held to a tenth of the
  // thinnest free block's thickness 2S/perimeter (half the side of a square).
  double limit = settings.maxDisplacementRatio * modelHalfSize();
  for (const Block& b : blocks)
    if (!b.fixed) limit = std::min(limit, 0.1 * 2 * b.moments.area / geometry::perimeter(b.vertices));
  return limit;
}

double Scene::normalPenalty() const {
  if (settings.penalty > 0) return settings.penalty;
  // A rigid stand-in (E above any rock's, RS2's 2e14 Pa) sets the contacts no stiffer than the
  // stiffest rock would: its blocks barely strain either way, and a penalty scaled to it would
  // be stiffer than the numbers resolve.
  double maxE = 0;
  for (const Material& m : materials) maxE = std::max(maxE, std::min(m.youngModulus, limits::kStiffestRock));
  return settings.penaltyFactor * maxE;
}

int Scene::blockIndex(const std::string& id) const {
  for (size_t i = 0; i < blocks.size(); ++i)
    if (blocks[i].id == id) return static_cast<int>(i);
  return -1;
}

SupportQuantity Scene::supportQuantity(const std::string& id) const {
  SupportQuantity q;
  for (const Support& s : supports)
    if (s.id == id) {
      q.kind = s.active() ? SupportQuantity::Kind::AnchorForce : SupportQuantity::Kind::BoltCapacity;
      q.name = s.active() ? "anchor force" : "bolt capacity";
      q.value = s.active() ? s.pretension : s.capacity;
      q.spacing = s.spacing;
      return q;
    }
  Vec2 resultant(0, 0);
  for (const PointLoad& l : pointLoads)
    if (l.id == id) q.kind = SupportQuantity::Kind::Load, resultant += l.force;
  if (q.kind == SupportQuantity::Kind::Load) {
    q.name = "load";
    q.value = resultant.norm();
  }
  return q;
}

void Scene::setSupportQuantity(const std::string& id, double value) {
  for (Support& s : supports)
    if (s.id == id) {
      if (s.active()) {
        s.pretension = value;
        s.capacity = std::max(s.capacity, value);
        s.force = value;
      } else {
        s.capacity = value;
      }
      return;
    }
  const double now = supportQuantity(id).value;
  // A load of no size has no direction to keep: it is left as it is (searches start above 0).
  if (!(now > 0)) return;
  for (PointLoad& l : pointLoads)
    if (l.id == id) l.force *= value / now, l.rate *= value / now;
}

std::vector<PointLoad> equivalentPointLoads(const EdgeLoad& l) {
  // Gauss points at ½ ± 1/(2√3) of the segment, weight ½ each.
  const double g = 0.5 / std::sqrt(3.0);
  const double length = (l.to - l.from).norm();
  std::vector<PointLoad> out;
  for (double t : {0.5 - g, 0.5 + g}) {
    PointLoad p;
    p.id = l.id;
    p.ofEdgeLoad = true;
    p.point.block = l.block;
    p.point.initial = p.point.current = l.from + t * (l.to - l.from);
    p.force = 0.5 * length * ((1 - t) * l.q0 + t * l.q1);
    out.push_back(p);
  }
  return out;
}

}  // namespace ddaslope::model
