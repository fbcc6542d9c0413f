#pragma once
// What the reader made of a case and what the user should know before trusting an answer:
// outline normalisation, concave kinks, joints ending on bends, the seismic loading in force.
#include <string>
#include <vector>

#include "ddaslope/model/scene.hpp"
#include "ddaslope/solver/simulation.hpp"

namespace ddaslope::cli {

/// A note per concave kink of a fixed block's surface with a block on it, and per joint the reader
/// moved off a bend.
/// check: each support (its blocks, length, force or capacity) and each edge load (its resultant).
void printSupportNotes(const ddaslope::model::Scene& scene);

void printKinkNotes(const model::Scene& scene);
/// What the reader did to the blocks' outlines, and the vertices it kept that bend a face so little
/// that the face still meets its neighbour as two contacts judged apart.
void printOutlineNotes(const model::Scene& scene);
/// The vertices that bend a touching face by less than the edge-parallel tolerance; empty if none.
std::string slightBendNote(const model::Scene& scene);
/// A warning for the searches where a joint ends on a concave bend (a corner in a notch); empty if
/// none.
std::string notchWarning(const model::Scene& scene);
/// For an answer: the joints the reader moved off concave bends (the answer is the moved
/// outline's, and an automatic move grows with the scene's size); empty if none.
std::string movedJointWarning(const model::Scene& scene);
/// Material and joint values that look like another unit's (t/m³, MPa, radians, kPa); empty if none.
std::string unitsWarning(const model::Scene& scene);
/// Contacts the automatic touching gap closed and bonded across gaps wider than 1e-6 w0 (from a
/// simulation's statistics at t = 0); empty if none.
std::string closedGapWarning(const model::Scene& scene, const solver::RunStatistics& st);
/// For a search: the notes on the contacts at t = 0, from one simulation set up as a trial's: the
/// contacts closed across gaps (closedGapWarning), and the named `joints` that no contact uses,
/// whose strength the answer cannot follow.
std::vector<std::string> contactsAtStartWarnings(const model::Scene& scene, const std::vector<int>& joints);
/// A warning when Δt exceeds the time in which a block falling freely from rest moves the step
/// limit, where answers stop holding (docs/accuracy.md, "Δt beyond the step limit"); empty if not.
std::string timeStepWarning(const model::Scene& scene);
/// For a search whose trials are each a minute's work or more between them: the size of one trial
/// (blocks, unknowns, contacts at t = 0, steps), said on stderr before it starts; nothing for a
/// small scene.
void saySearchSize(const model::Scene& scene);
/// The water in force: the tension crack (its position, depth and water), and on each face of a
/// free block below the water its resultant and greatest pressure, named by the block or joint it
/// meets (the pressure on each joint), or as a free face.
void printWaterNotes(const model::Scene& scene);
/// For a command whose runs keep the case's crack where the case puts it (probability,
/// backanalyse) although the case asks for its position to be searched: says so; empty otherwise.
/// `varied`: the case numbers the command itself sets run by run; with section.tension_crack.x
/// among them the crack moves as they say, and the note says that instead.
std::string fixedCrackNote(const model::Scene& scene, const std::vector<std::string>& varied = {});
/// The seismic loading in force: the coefficients and the record's span and peaks.
void printSeismicNote(const model::Scene& scene);

}  // namespace ddaslope::cli
