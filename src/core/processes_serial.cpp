// The processes of a build without MPI: one.
#include <cstdlib>

#include "ddaslope/core/task_farm.hpp"

namespace ddaslope {

void startProcesses(int&, char**&) {}
void stopProcesses() {}
int processRank() { return 0; }
int processCount() { return 1; }
void abortProcesses(int code) { std::exit(code); }
bool errorSharedByAllProcesses() { return false; }
void declareErrorShared() {}
std::string processSupport() { return "without MPI"; }
std::unique_ptr<TaskFarm> makeTaskFarm(int threads) { return makeThreadFarm(threads); }

}  // namespace ddaslope
