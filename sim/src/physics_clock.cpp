// Box2D's step profiler without the wall clock.
//
// b2World::Step times its phases for b2World::GetProfile with b2Timer, which on Linux reads gettimeofday about ten
// times per step (10 % of a social episode's time). Nothing in freeplay reads the profile, and simulation code
// must not read the wall clock, so this definition of b2Timer replaces the library's: the executable's copy is the
// one Box2D's calls bind to (sim/CMakeLists.txt links it in and exports it). The profile then reads zero.

#include <box2d/b2_timer.h>

b2Timer::b2Timer() : m_start_sec(0), m_start_usec(0) {}

void b2Timer::Reset() {}

float b2Timer::GetMilliseconds() const { return 0.0F; }
