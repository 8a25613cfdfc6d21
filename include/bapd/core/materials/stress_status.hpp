#pragma once
// What a constitutive model reports for one bond (material.hpp describes the model
// interface). The bond kernels only need this header, not the laws.

namespace bapd {

enum class StressStatus : int {
  ok             = 0,
  chain_limit    = 1, // the law has no finite energy here (Gent: I1bar - 3 >= Jm)
  inverted       = 2, // det F <= 0
  no_convergence = 3  // the plane-stress C33 solve did not converge
};
// A stress the law cannot give: P zeroed (no bond force from it), s returned.
template <class Stress> StressStatus stress_failed(Stress &P, StressStatus s)
{
  P = {};
  return s;
}
// Short name ("ok", "chain_limit", ...), for logs and CSV.
const char *to_string(StressStatus s);
// One sentence for a run that must stop: what happened and which option changes it.
const char *describe(StressStatus s);

} // namespace bapd
