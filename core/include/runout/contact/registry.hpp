// The contact laws runout knows: one row per law, and nothing else to edit to add one
// (write its header after walton_braun.hpp or cundall_strack.hpp, add it to its list here).
// A row is the law's type: its name (the scene's contact.normal_model, tangential_model or
// rolling_model), how its Params come from the scene's knobs (Law::params, Law::design), the
// stiffness it contributes to tau_min (Law::stiffness_for_dt) and, through `dispatch`, the
// kernel instantiated for it.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "runout/contact/contact.hpp"
#include "runout/contact/cundall_strack.hpp"
#include "runout/contact/hertz.hpp"
#include "runout/contact/linear_dashpot.hpp"
#include "runout/contact/mindlin.hpp"
#include "runout/contact/rolling_sds.hpp"
#include "runout/contact/walton_braun.hpp"

namespace runout {

template <class... Laws>
struct LawList {
  static std::vector<std::string> names() { return {Laws::kName...}; }
  static bool known(const std::string& name) {
    return ((name == Laws::kName) || ...);
  }
  // Calls f(Law{}) for the law called `name`; false if there is none.
  template <class F>
  static bool with(const std::string& name, F&& f) {
    return ((name == Laws::kName ? (f(Laws{}), true) : false) || ...);
  }
};

using NormalLaws = LawList<WaltonBraun, LinearDashpot, Hertz>;
using TangentialLaws = LawList<CundallStrack, Mindlin>;
using RollingLaws = LawList<NoRolling, RollingSpringDashpot>;

// The laws a scene chose (names checked by the scene reader against the lists above).
struct ContactChoice {
  std::string normal = "walton_braun", tangential = "cundall_strack", rolling = "none";
  bool frictional = true;  // false: mu = 0 everywhere, the Frictionless law is used
};

// Calls f(ContactModel<N, T, R>{}) for the chosen laws. One place instantiates every kernel.
template <class F>
void dispatch(const ContactChoice& c, F&& f) {
  NormalLaws::with(c.normal, [&](auto normal) {
    using N = decltype(normal);
    RollingLaws::with(c.rolling, [&](auto rolling) {
      using R = decltype(rolling);
      if (!c.frictional) {
        f(ContactModel<N, Frictionless, R>{});
        return;
      }
      TangentialLaws::with(c.tangential, [&](auto tangential) {
        f(ContactModel<N, decltype(tangential), R>{});
      });
    });
  });
}

}  // namespace runout
