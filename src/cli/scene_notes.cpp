#include "scene_notes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "crack_search.hpp"
#include "ddaslope/assembly/water_terms.hpp"
#include "ddaslope/geometry/polygon.hpp"
#include "ddaslope/io/ground_motion.hpp"
#include "ddaslope/model/kinks.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::cli {
namespace {

/// Whether point p of block `own` lies on or near (1e-3 w0) the outline of another block.
bool touchesAnotherBlock(const ddaslope::model::Scene& scene, const ddaslope::model::Block& own, const ddaslope::Vec2& p) {
  const double near = 1e-3 * scene.modelHalfSize();
  for (const auto& b : scene.blocks) {
    if (&b == &own || (b.fixed && own.fixed)) continue;
    for (size_t k = 0; k < b.vertices.size(); ++k)
      if (ddaslope::geometry::distanceToSegment(p, b.vertices[k], b.vertices[(k + 1) % b.vertices.size()], nullptr) <= near)
        return true;
  }
  return false;
}

}  // namespace

/// A note per concave kink of the sliding surface with a block on it: there the block model leans on
/// a corner that limit-equilibrium slices cannot, so their critical strengths differ.
void printKinkNotes(const ddaslope::model::Scene& scene) {
  const double failure = scene.settings.failureDisplacement > 0 ? scene.settings.failureDisplacement
                                                                 : 1e-3 * scene.modelHalfSize();
  const double near = 1e-6 * scene.modelHalfSize();
  for (const auto& m : scene.movedJointEnds)
    std::printf("  outlines: the joint between %s and %s ended on a concave bend of %s at (%g, %g); it is moved %.3g m up "
                "the upper face%s, so that %s owns the bend and %s slides on without a corner in the notch "
                "(docs/research/bilinear-slab.md; analysis.joint_end_offset 0 keeps it where it was drawn)\n",
                scene.blocks[m.upper].id.c_str(), scene.blocks[m.lower].id.c_str(), scene.blocks[m.fixedBlock].id.c_str(),
                m.kink.x() + scene.origin.x(), m.kink.y() + scene.origin.y(), m.shift.norm(),
                m.parallel ? ", parallel to itself" : ", turning about its other end", scene.blocks[m.lower].id.c_str(),
                scene.blocks[m.upper].id.c_str());
  for (const auto& k : ddaslope::model::concaveKinksUnderBlocks(scene)) {
    if (std::any_of(scene.movedJointEnds.begin(), scene.movedJointEnds.end(),
                    [&](const auto& m) { return (m.kink - k.point).norm() <= near; }))
      continue;
    std::printf("  note: the surface of %s bends up by %.1f° at (%g, %g), where a block reaching %.3g m up the slope "
                "has a corner. ",
                scene.blocks[k.fixedBlock].id.c_str(), k.bendDeg, k.point.x() + scene.origin.x(),
                k.point.y() + scene.origin.y(), k.upslopeReach);
    if (k.upslopeReach <= failure)
      std::printf("That is no more than the verdict's failure displacement (%.3g m): a slide can squeeze the block out "
                  "and rest on the next corner without being called failing. Make it wider (docs/case-format.md, "
                  "\"Kink blocks\")\n", failure);
    else if (k.upslopeReach < 0.1 * k.reachingBlockHeight)
      std::printf("A block that thin (a kink block) leans on it little (docs/calibration.md, \"The chair-shaped "
                  "slide\")\n");
    else if (k.blocksWithCorner >= 2)
      std::printf("%d blocks meet there: a joint ends on the bend, so the block above has its corner in the notch and "
                  "touches both faces. It cannot slide on along the upper face without lifting or bending, which a DDA "
                  "block (uniform strain) cannot do, and F may then follow the contact stiffness: compare "
                  "analysis.penalty_factor 10-2000 and the blocks' own bound (scripts/block_equilibrium.py). The reader "
                  "moves such a joint up the upper face where one block lies on each face (analysis.joint_end_offset, "
                  "here 0 or not possible); a kink block would make another block system (docs/research/bilinear-slab.md)\n",
                  k.blocksWithCorner);
    else
      std::printf("The block may lean on that corner, which limit-equilibrium slices cannot, with a force its width "
                  "sets. On a kink inside the sliding surface a thin block there (section.kink_block_width) takes "
                  "most of that away (docs/calibration.md, \"The chair-shaped slide\"; scripts/block_equilibrium.py "
                  "gives these blocks' own bound)\n");
  }
}

/// The vertices the reader kept that bend a face touching another block by less than the
/// edge-parallel tolerance: the face then meets its neighbour as two contacts judged apart. Empty
/// if none.
std::string slightBendNote(const ddaslope::model::Scene& scene) {
  int slight = 0;
  double offLine = 0;
  std::string first;
  for (const auto& b : scene.blocks) {
    const size_t n = b.vertices.size();
    for (size_t k = 0; k < n; ++k) {
      const ddaslope::Vec2 in = b.vertices[k] - b.vertices[(k + n - 1) % n], out = b.vertices[(k + 1) % n] - b.vertices[k];
      const double turnDeg = std::abs(std::atan2(ddaslope::cross(in, out), in.dot(out))) * 180 / M_PI;
      if (turnDeg >= scene.settings.edgeParallelToleranceDeg || !touchesAnotherBlock(scene, b, b.vertices[k])) continue;
      // How far it lies off its neighbours' chord: the gap initial_contact_tolerance would have to
      // count as touching for the reader to take it as on the line.
      const ddaslope::Vec2 chord = b.vertices[(k + 1) % n] - b.vertices[(k + n - 1) % n];
      offLine = std::max(offLine, std::abs(ddaslope::cross(chord, b.vertices[k] - b.vertices[(k + n - 1) % n])) / chord.norm());
      if (slight++ == 0) {
        char where[160];
        std::snprintf(where, sizeof where, "block %s at (%g, %g), %.3g°", b.id.c_str(),
                      b.vertices[k].x() + scene.origin.x(), b.vertices[k].y() + scene.origin.y(), turnDeg);
        first = where;
      }
    }
  }
  if (slight == 0) return "";
  std::ostringstream m;
  m << slight << " vertices bend their block's outline by less than the edge-parallel tolerance ("
    << scene.settings.edgeParallelToleranceDeg << "°) but are not on a straight line (first: " << first
    << "): each splits a face into contacts judged apart, whose cohesion may fail piecewise. They lie up to "
    << offLine << " m off a straight line; if that is rounding, `--set analysis.initial_contact_tolerance="
    << std::ceil(2 * offLine / scene.modelHalfSize() * 1e9) / 1e9
    << "` (gaps that count as touching at t = 0, as a fraction of w0) takes them as on it";
  return m.str();
}

/// What the reader did to the blocks' outlines, and the vertices it kept that bend a face so little
/// that the face still meets its neighbour as two contacts judged apart.
void printOutlineNotes(const ddaslope::model::Scene& scene) {
  int removed = 0, blocks = 0;
  for (const auto& b : scene.blocks) removed += b.removedCollinearVertices, blocks += b.removedCollinearVertices > 0;
  if (removed > 0)
    std::printf("  outlines: %d vertices on straight edges removed from %d block(s) (T-junctions and split edges: each "
                "face meets its neighbour as one contact, docs/contact-model.md)\n",
                removed, blocks);
  for (const auto& b : scene.blocks)
    if (!b.mergedIds.empty()) {
      std::string ids;
      for (const std::string& id : b.mergedIds) ids += (ids.empty() ? "" : ", ") + id;
      std::printf("  fixed blocks %s merged into %s: they share boundary and meet every block with the same joint, so "
                  "a block across their seam meets them as one contact (docs/contact-model.md)\n",
                  ids.c_str(), b.id.c_str());
    }
  if (const std::string note = slightBendNote(scene); !note.empty()) std::printf("  note: %s\n", note.c_str());
}

/// A warning for the searches where a joint ends on a concave bend of the sliding surface (a
/// corner in a notch: F may follow the contact stiffness, docs/research/bilinear-slab.md).
std::string notchWarning(const ddaslope::model::Scene& scene) {
  for (const auto& k : ddaslope::model::concaveKinksUnderBlocks(scene))
    if (k.blocksWithCorner >= 2 && k.upslopeReach >= 0.1 * k.reachingBlockHeight) {
      std::ostringstream m;
      m << "a joint ends on a concave bend of " << scene.blocks[k.fixedBlock].id << " at (" << k.point.x() + scene.origin.x()
        << ", " << k.point.y() + scene.origin.y() << "): a corner sits in the notch, and the answer may follow the "
        << "contact stiffness; compare analysis.penalty_factor 10-2000 and scripts/block_equilibrium.py --solve fos "
           "(`ddaslope check` says more)";
      return m.str();
    }
  return "";
}

std::string movedJointWarning(const ddaslope::model::Scene& scene) {
  if (scene.movedJointEnds.empty()) return "";
  const auto& m = scene.movedJointEnds.front();
  std::ostringstream w;
  w.precision(3);
  w << "the joint between " << scene.blocks[m.upper].id << " and " << scene.blocks[m.lower].id
    << " ended on a concave bend of " << scene.blocks[m.fixedBlock].id << " at (" << std::setprecision(10)
    << m.kink.x() + scene.origin.x() << ", " << m.kink.y() + scene.origin.y() << std::setprecision(3)
    << ") and was moved " << m.shift.norm() << " m up the upper face";
  if (scene.movedJointEnds.size() > 1) w << " (and " << scene.movedJointEnds.size() - 1 << " more)";
  w << ": the answer is that of the moved outline, not the drawn one, where a corner in the notch would follow the "
       "contact stiffness (docs/research/bilinear-slab.md). ";
  if (scene.settings.jointEndOffset < 0)
    w << "The move is analysis.joint_end_offset's automatic max(5e-3 w0, 2 × failure displacement), which grows with "
         "the whole scene's size, the fixed blocks' included: set it (e.g. `--set analysis.joint_end_offset=X`, X well "
         "above the slide's settling) and compare";
  else
    w << "Compare another analysis.joint_end_offset";
  return w.str();
}

std::string unitsWarning(const ddaslope::model::Scene& scene) {
  std::ostringstream m;
  m.precision(4);
  int found = 0;
  const auto add = [&](const std::string& what) { m << (found++ ? "; " : "") << what; };
  if (scene.gravity.y() > 0) add("gravity points upward (gravity[1] > 0: [0, -9.81] is downward)");
  for (const auto& mat : scene.materials) {
    std::ostringstream w;
    w.precision(4);
    if (mat.density > 0 && (mat.density < 500 || mat.density > 10000)) {
      w << "materials." << mat.name << ".density = " << mat.density << " kg/m³ (rock is about 1800-3000; t/m³ are 1000 kg/m³)";
      add(w.str());
      w.str("");
    }
    if (mat.youngModulus > 0 && mat.youngModulus < 1e6) {
      w << "materials." << mat.name << ".young_modulus = " << mat.youngModulus
        << " Pa (rock masses are about 1e8-1e11 Pa; MPa are 1e6 Pa, GPa 1e9)";
      add(w.str());
    }
  }
  double densest = 0;
  for (const auto& mat : scene.materials) densest = std::max(densest, mat.density);
  for (const auto& j : scene.joints) {
    std::ostringstream w;
    w.precision(4);
    const double phi = ddaslope::radToDeg(j.frictionAngle);
    if (!j.bartonBandis && phi > 0 && phi < 1.6) {
      w << "joints." << j.name << ".friction_angle = " << phi << "° (degrees are read; " << phi << " rad would be "
        << ddaslope::radToDeg(phi) << "°)";
      add(w.str());
    }
    // Against the weight stress of the model's size: 40 Pa is a laboratory joint's cohesion under
    // a 5 cm brick, and a slip of units under a 100 m slope.
    if (j.cohesion > 0 && j.cohesion < 1e-4 * densest * scene.gravity.norm() * scene.modelHalfSize()) {
      w.str("");
      w << "joints." << j.name << ".cohesion = " << j.cohesion << " Pa (Pa are read; " << j.cohesion << " kPa would be "
        << std::setprecision(10) << j.cohesion * 1e3 << " Pa)";
      add(w.str());
    }
  }
  // Water given in other coordinates than the blocks': a level or line below every free block
  // (a datum shifted down, the wrong sign), which wets none of them at the start (and never, when
  // it does not vary); or a pressure grid with none of its points near them, whose pressures
  // there are its fitted plane's extrapolation.
  if (scene.water.active() && scene.water.seriesLevels.empty()) {
    ddaslope::geometry::Aabb free{{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
    bool wets = false;
    const ddaslope::model::WaterTable water = scene.water.at(0);
    for (const auto& b : scene.blocks) {
      if (b.fixed) continue;
      const ddaslope::geometry::Aabb bb = ddaslope::geometry::boundingBox(b.vertices);
      free.lo = free.lo.cwiseMin(bb.lo), free.hi = free.hi.cwiseMax(bb.hi);
      for (size_t k = 0; k < b.vertices.size() && !wets; ++k)
        wets = ddaslope::assembly::edgeWaterResultant(b.vertices[k], b.vertices[(k + 1) % b.vertices.size()], water).norm() > 0;
    }
    if (scene.water.grid) {
      const double reach = (free.hi - free.lo).maxCoeff();
      bool near = false;
      for (const Vec2& p : scene.water.grid->points())
        near = near || (p.x() >= free.lo.x() - reach && p.x() <= free.hi.x() + reach && p.y() >= free.lo.y() - reach &&
                        p.y() <= free.hi.y() + reach);
      if (!near && std::isfinite(reach))
        add("water.pressure_grid has no point within the free blocks' size of them: its pressures there are its fitted "
            "plane's, extrapolated (are its points in the model's coordinates?)");
    } else if (!wets && std::isfinite(free.lo.x())) {
      add("the water wets no free block: every free block lies above it (are its elevations in the model's coordinates?)");
    }
  }
  if (found == 0) return "";
  return "values to check, another unit or a slip: " + m.str();
}

std::string closedGapWarning(const ddaslope::model::Scene& scene, const ddaslope::solver::RunStatistics& st) {
  if (scene.settings.initialContactTolerance >= 0 || st.closedAcrossGaps == 0) return "";
  std::ostringstream m;
  m.precision(3);
  m << st.closedAcrossGaps << (st.closedAcrossGaps == 1 ? " contact starts" : " contacts start")
    << " closed and bonded across gaps of up to " << st.widestClosedGap * 1e3
    << " mm: the default touching gap (" << scene.touchingGap() * 1e3
    << " mm) takes them for coordinates rounded to the millimetre. If they are real openings, "
       "`--set analysis.initial_contact_tolerance=1e-6` keeps them open";
  return m.str();
}

namespace {
/// The named joints that no contact of `sim` (at t = 0) uses; empty if every one has one.
std::string untouchedJointsWarning(const ddaslope::model::Scene& scene, const ddaslope::solver::Simulation& sim,
                                   const std::vector<int>& joints) {
  std::vector<std::string> untouched;
  for (const int j : joints) {
    bool found = false;
    for (const auto& c : sim.contacts().contacts()) found |= c.joint == j;
    if (!found) untouched.push_back(scene.joints[static_cast<size_t>(j)].name);
  }
  if (untouched.empty()) return "";
  std::ostringstream m;
  for (size_t k = 0; k < untouched.size(); ++k) m << (k ? ", " : "joint ") << untouched[k];
  m << (untouched.size() > 1 ? " have" : " has")
    << " no contact at t = 0 (no two blocks it joins touch or lie within the contact search distance): its strength "
       "cannot change this answer unless blocks move into contact. Check the joint's name and joint_pairs (`ddaslope "
       "check` lists the contacts)";
  return m.str();
}
}  // namespace

std::vector<std::string> contactsAtStartWarnings(const ddaslope::model::Scene& scene, const std::vector<int>& joints) {
  if (scene.settings.initialContactTolerance >= 0 && joints.empty()) return {};
  const ddaslope::solver::Simulation sim(scene);  // the contacts at t = 0, found as a trial finds them
  std::vector<std::string> out;
  for (std::string w : {closedGapWarning(scene, sim.statistics()), untouchedJointsWarning(scene, sim, joints)})
    if (!w.empty()) out.push_back(std::move(w));
  return out;
}

std::string timeStepWarning(const ddaslope::model::Scene& scene) {
  const double g = scene.gravity.norm();
  if (!(g > 0) || scene.blocks.empty()) return "";
  // Beyond this Δt every step of a block set moving is cut to the step limit, and a trial's
  // verdict no longer follows its strengths: measured on Vajont (docs/accuracy.md), F stayed
  // 1.1224 up to Δt = 0.36 of it and was 1.50 at 1.07 of it, none at 3.6 and 3.92 at 36.
  const double limit = scene.stepLimit();
  const double fall = std::sqrt(2 * limit / g);
  if (scene.settings.timeStep <= fall) return "";
  std::ostringstream m;
  m.precision(3);
  m << "analysis.time_step " << scene.settings.timeStep << " s is longer than the " << fall
    << " s in which a block falling freely from rest moves the step limit (" << limit
    << " m): steps of moving blocks are cut, and failures and factors of safety at this Δt may not follow the "
       "strengths (Vajont's F went from 1.12 to 1.50 at a Δt of 1.07 times that time; docs/accuracy.md). Use a Δt below "
    << fall << " s (or drop analysis.time_step: the preset's)";
  return m.str();
}

void saySearchSize(const ddaslope::model::Scene& scene) {
  // A search runs ten to twenty trials; at ~10 µs per block and step on one core
  // (docs/performance.md) a trial of 5e5 block-steps makes the search a minute or more.
  const double steps = scene.settings.duration / scene.settings.timeStep + scene.settings.equilibriumMaxSteps;
  if (!(steps * static_cast<double>(scene.blocks.size()) > 5e5)) return;
  const ddaslope::solver::Simulation sim(scene);  // the contacts at t = 0, found as a trial finds them
  std::ostringstream m;
  m.precision(3);
  m << "ddaslope: a long search: each trial is " << scene.blocks.size() << " blocks (" << scene.freeUnknowns() << " unknowns), "
    << sim.contacts().contacts().size() << " contacts at t = 0, up to " << scene.settings.equilibriumMaxSteps
    << " steps of initial equilibrium and " << std::llround(scene.settings.duration / scene.settings.timeStep) << " steps of "
    << scene.settings.timeStep << " s; a search runs ten to twenty trials\n";
  std::fputs(m.str().c_str(), stderr);
}

/// The seismic loading in force: the coefficients and the record's span and peaks.
void printSeismicNote(const ddaslope::model::Scene& scene) {
  const ddaslope::model::SeismicLoad& q = scene.seismic;
  if (q.kh != 0 || q.kv != 0)
    std::printf("  pseudo-static seismic load: k_h = %g (a force along %s), k_v = %g (%s), from the initial equilibrium on\n",
                q.kh, q.kh < 0 ? "-x" : "+x", q.kv, q.kv < 0 ? "downward" : "upward");
  if (!q.ground.active()) return;
  double ph = 0, pv = 0;
  for (double a : q.ground.horizontal) ph = std::max(ph, std::abs(a));
  for (double a : q.ground.vertical) pv = std::max(pv, std::abs(a));
  std::printf("  ground-motion record: %zu samples over t = %g-%g s of the analysis, peak %.4g m/s² (%.3g g) horizontal",
              q.ground.times.size(), q.ground.times.front(), q.ground.times.back(), ph, ph / ddaslope::io::kStandardGravity);
  if (!q.ground.vertical.empty()) std::printf(", %.4g m/s² (%.3g g) vertical", pv, pv / ddaslope::io::kStandardGravity);
  std::printf("\n");
  // What a user may not expect of a record (docs/seismic.md).
  const ddaslope::Vec2 first = q.ground.at(q.ground.times.front());
  if (first.norm() > 1e-3 * std::max(ph, pv))
    std::printf("  note: the record starts at %.4g m/s², not 0: a step load, which rings the contact springs; taper it in\n",
                first.norm());
  if (q.ground.times.front() >= scene.settings.duration)
    std::printf("  note: the record starts at t = %g s, after the analysis ends (analysis.duration %g s): it never acts\n",
                q.ground.times.front(), scene.settings.duration);
  double sample = INFINITY;
  for (size_t k = 1; k < q.ground.times.size(); ++k) sample = std::min(sample, q.ground.times[k] - q.ground.times[k - 1]);
  if (scene.settings.timeStep > sample * (1 + 1e-6))  // the samples' times carry their text's round-off
    std::printf("  note: Δt %g s is longer than the record's sampling (%g s): each step applies the record's mean over "
                "the step, so content above %.3g Hz is averaged out\n",
                scene.settings.timeStep, sample, 0.5 / scene.settings.timeStep);
}

void printSupportNotes(const ddaslope::model::Scene& scene) {
  for (const auto& b : scene.supports) {
    std::printf("  support %s: from block %s to block %s, %.4g m; ", b.id.c_str(), scene.blocks[b.head.block].id.c_str(),
                scene.blocks[b.end.block].id.c_str(), b.initialLength);
    if (b.stiffness > 0) std::printf("stiffness %.4g N/m per m, ", b.stiffness);
    if (b.pretension > 0) std::printf("pretension %.4g kN/m, ", b.pretension / 1e3);
    if (std::isfinite(b.capacity))
      std::printf("capacity %.4g kN/m (%s beyond)", b.capacity / 1e3,
                  b.failure == ddaslope::model::SupportFailure::Rupture ? "ruptures" : "yields");
    else
      std::printf("no capacity limit");
    if (std::isfinite(b.bondStrength))
      std::printf("; bond over %.3g m in the head's block and %.3g m in the end's", b.headEmbedment, b.endEmbedment);
    std::printf("; per metre of slope (spacing %g m)\n", b.spacing);
    if (b.stiffness <= 0 && b.pretension <= 0)
      std::printf("  note: support %s has neither stiffness nor pretension: it carries nothing\n", b.id.c_str());
  }
  for (const auto& l : scene.edgeLoads) {
    const ddaslope::Vec2 r = l.resultant();
    std::printf("  edge load%s%s on block %s: resultant (%.4g, %.4g) kN/m%s\n", l.id.empty() ? "" : " ", l.id.c_str(),
                scene.blocks[l.block].id.c_str(), r.x() / 1e3, r.y() / 1e3,
                scene.blocks[l.block].fixed ? ": the block is fixed, so the load does nothing" : "");
  }
  // Point loads of the case itself (an edge load's Gauss points are shown as the edge load).
  for (const auto& l : scene.pointLoads) {
    if (l.ofEdgeLoad) continue;
    std::printf("  point load%s%s on block %s at (%.6g, %.6g): (%.4g, %.4g) kN/m%s\n", l.id.empty() ? "" : " ",
                l.id.c_str(), scene.blocks[l.point.block].id.c_str(), l.point.initial.x() + scene.origin.x(),
                l.point.initial.y() + scene.origin.y(), l.force.x() / 1e3, l.force.y() / 1e3,
                scene.blocks[l.point.block].fixed ? ": the block is fixed, so the load does nothing" : "");
  }
}

std::string fixedCrackNote(const ddaslope::model::Scene& scene, const std::vector<std::string>& varied) {
  if (!scene.crackSearch || !scene.tensionCrack) return "";
  char text[256];
  for (const char* place : {"section.tension_crack.x", "section.tension_crack.depth"})
    if (std::find(varied.begin(), varied.end(), place) != varied.end()) {
      std::snprintf(text, sizeof text,
                    "the tension crack is where each run's %s puts it: section.tension_crack.search over [%g, %g] m is "
                    "used only by fos and critical",
                    place, scene.crackSearch->first, scene.crackSearch->second);
      return text;
    }
  std::snprintf(text, sizeof text,
                "the tension crack stays at x = %g m (%s) in every run: only fos and critical search its position over "
                "[%g, %g] m",
                scene.tensionCrack->x, ddaslope::cli::crackPlacement(scene).c_str(), scene.crackSearch->first, scene.crackSearch->second);
  return text;
}

void printWaterNotes(const ddaslope::model::Scene& scene) {
  const Vec2 o = scene.origin;
  if (const auto& c = scene.tensionCrack) {
    std::printf("  tension crack at x = %g m: %g m deep (ground %g m, sliding surface %g m), water %g m deep in it "
                "(fraction %g%s), open by %g m\n",
                c->x, c->depth(), c->top, c->bottom, c->waterDepth(), c->waterFraction,
                c->waterFraction > 0 ? ", draining along the sliding surface to the toe" : "", c->gap);
    if (scene.crackSearch)
      std::printf("  fos and critical search the crack's position in x = [%g, %g] m for the least safe%s\n",
                  scene.crackSearch->first, scene.crackSearch->second,
                  c->x < scene.crackSearch->first || c->x > scene.crackSearch->second
                      ? " (the crack above, which the other commands use, lies outside that range)"
                      : "");
  }
  if (!scene.water.active()) return;
  const ddaslope::model::WaterTable water = scene.water.at(0);
  const double near = 1e-6 * scene.modelHalfSize();
  for (const auto& b : scene.blocks) {
    if (b.fixed) continue;
    for (size_t k = 0; k < b.vertices.size(); ++k) {
      const Vec2 &a = b.vertices[k], &e = b.vertices[(k + 1) % b.vertices.size()];
      const Vec2 r = ddaslope::assembly::edgeWaterResultant(a, e, water);
      if (r.norm() == 0) continue;
      // What the face meets: another block along its middle, or nothing.
      const Vec2 mid = 0.5 * (a + e);
      std::string meets = "free face";
      if (const auto& c = scene.tensionCrack; c && std::abs(a.x() + o.x() - c->x) <= near && std::abs(e.x() + o.x() - c->x) <= near)
        meets = "the tension crack";
      for (size_t j = 0; j < scene.blocks.size(); ++j) {
        const auto& other = scene.blocks[j];
        if (&other == &b) continue;
        bool on = false;
        for (size_t m = 0; m < other.vertices.size() && !on; ++m)
          on = ddaslope::geometry::distanceToSegment(mid, other.vertices[m], other.vertices[(m + 1) % other.vertices.size()],
                                                     nullptr) <= near;
        if (!on) continue;
        const int own = static_cast<int>(&b - scene.blocks.data());
        meets = "on " + other.id + ", joint " + scene.joints[scene.jointBetween(own, static_cast<int>(j))].name;
        break;
      }
      std::printf("  water on %s, face (%g, %g)-(%g, %g) (%s): %.4g kN/m, up to %.4g kPa\n", b.id.c_str(), a.x() + o.x(),
                  a.y() + o.y(), e.x() + o.x(), e.y() + o.y(), meets.c_str(), r.norm() / 1e3,
                  std::max(water.pressureAt(a), water.pressureAt(e)) / 1e3);
    }
  }
}

}  // namespace ddaslope::cli
