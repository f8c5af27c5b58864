// One way to spread independent jobs over the machine's cores, for the library's long loops (the
// preview's rows, the glTF fits, the comparison's reference estimates) and the tests.
#pragma once

#include <cstddef>
#include <functional>

namespace lamina {

// Runs job(0) .. job(count - 1), each once, on up to one thread per core (at most 16), every
// thread taking the next index from a shared counter. A job must write only its own results, so
// that what the jobs compute does not depend on the schedule. If jobs throw, the indices not yet
// taken are skipped and the first exception is rethrown once every thread has ended.
void parallel_for(size_t count, const std::function<void(size_t)>& job);
// The same on at most `threads` threads (0: one per core, as above).
void parallel_for(size_t count, const std::function<void(size_t)>& job, size_t threads);

}  // namespace lamina
