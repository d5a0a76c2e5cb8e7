// The API of the other published variant of <utility/sct.h>, the one the multi-human swarm control
// controllers use (docs/compat.md): sct.h builds its SCT on this when SWARMVM_SCT_VARIANT_MHSC is
// defined. The step is the same; two things differ from the default variant:
//   sct->add_callback(this, sct->events["EV_x"], &C::cb, NULL, NULL);   // by event index
//   sct->get_current_state_string();                                   // "sup:[3,0,2]": from 0
// Registration by name is the default variant's API, refused here at compile time with a hint,
// so a controller built with the wrong variant never runs with the other numbering.
#ifndef SWARMVM_SCT_MHSC_HPP
#define SWARMVM_SCT_MHSC_HPP

#include <algorithm>
#include <cstddef>
#include <map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "swarmvm.hpp"

namespace swarmvm {

// `Base` is a compatibility SCT (BasicSCT's public API: events, add_callback by name,
// get_current_state_string); this adds the variant's API on top of it.
template <class Base>
class MhscSCT : public Base {
public:
    // Controllable event: an action, no check.
    template <class C>
    void add_callback(C* p, std::size_t event, void (C::*clbk)(void*), void* no_check, void* data) {
        Base::add_callback(p, name_of(event), clbk, no_check, data);
    }
    // Uncontrollable event: a check, no action.
    template <class C, class R>
    void add_callback(C* p, std::size_t event, void* no_action, R (C::*ci)(void*), void* data) {
        Base::add_callback(p, name_of(event), no_action, ci, data);
    }
    // Both a check and an action.
    template <class C, class R>
    void add_callback(C* p, std::size_t event, void (C::*clbk)(void*), R (C::*ci)(void*), void* data) {
        Base::add_callback(p, name_of(event), clbk, ci, data);
    }
    template <class C, class N, class A, class K,
              std::enable_if_t<std::is_convertible<N, std::string>::value, int> = 0>
    void add_callback(C*, N, A, K, void*) {
        static_assert(!std::is_convertible<N, std::string>::value,
                      "sct.h: callbacks registered by event name are the default variant's API; build without "
                      "SWARMVM_SCT_VARIANT_MHSC (docs/compat.md)");
    }

    // The published variant prints sup_current_state[i] where the default one prints
    // sup_current_state[i] + 1: the same string with every number one less.
    std::string get_current_state_string() override {
        static const char* const digits = "0123456789";
        const std::string from_one = Base::get_current_state_string();   // "sup:[4,1,3]"
        std::string out;
        std::size_t at = 0;
        for (std::size_t first; (first = from_one.find_first_of(digits, at)) != std::string::npos;) {
            out += from_one.substr(at, first - at);
            at = std::min(from_one.find_first_not_of(digits, first), from_one.size());
            out += std::to_string(std::stoul(from_one.substr(first, at - first)) - 1);
        }
        out += from_one.substr(at);
        return out;
    }

protected:
    template <class... Args>
    explicit MhscSCT(Args&&... args) : Base(std::forward<Args>(args)...) {
        names_.resize(this->events.size());
        for (const auto& entry : this->events) names_[entry.second] = entry.first;
    }

private:
    // The name of the event a caller's index stands for. `sct->events["EV_typo"]` inserts the
    // unknown name with index 0 (the published VM then silently registers event 0): here it is
    // an UnknownEvent naming it, as an unknown name is in the default variant.
    const std::string& name_of(std::size_t event) const {
        if (this->events.size() != names_.size()) {
            for (const auto& entry : this->events) {
                if (entry.second >= names_.size() || names_[entry.second] != entry.first) {
                    throw UnknownEvent("no event named '" + entry.first + "' in this supervisor");
                }
            }
        }
        if (event >= names_.size()) {
            throw UnknownEvent("no event with index " + std::to_string(event) + " in this supervisor");
        }
        return names_[event];
    }

    std::vector<std::string> names_;   // event index -> name, as `events` maps them
};

}  // namespace swarmvm

#endif  // SWARMVM_SCT_MHSC_HPP
