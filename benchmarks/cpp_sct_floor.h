// The floor of an exact step on two tiny corpus supervisors, for benchmarks/cpp_steps.py: an
// `SCT` with the published API, written by hand for one supervisor (no tables, no search), that
// makes only what any VM stepping as the published one must make in benchmarks/cpp_sct_steps.cpp
// — the registered check, called through the registered member function; the ARGoS draw, when
// and as often as the published VM draws; the action of the event applied — and prints the
// published state string, so the driver's checksum shows it made the published steps.
// Built in place of sct.h with -DSWARMVM_FLOOR_PUBLIC_EXAMPLE (tests/corpus/nadzoru2/public_example.yaml)
// or -DSWARMVM_FLOOR_PROBABILISTIC_EXAMPLE (probabilistic_example.yaml). Its steps per second over
// the published VM's bound what any drop-in can reach on that supervisor in that driver.
#ifndef SWARMVM_SCT_FLOOR_H
#define SWARMVM_SCT_FLOOR_H

#include <map>
#include <string>
#include <vector>

#include "swarmvm_argos.hpp"

class SCT {
public:
    explicit SCT(const std::string& /*yaml_path: the supervisor is built in*/)
        : rng_(argos::CRandom::CreateRNG("argos")), registrations_(kEvents.size()) {
        for (std::size_t e = 0; e < kEvents.size(); ++e) events[kEvents[e]] = e;
    }
    virtual ~SCT() = default;

    template <class C>
    void add_callback(C* p, const std::string& event, void (C::*action)(void*), void*, void* data) {
        registrations_[events.at(event)].set_action(p, action);
        registrations_[events.at(event)].data = data;
    }
    template <class C, class R>
    void add_callback(C* p, const std::string& event, void*, R (C::*check)(void*), void* data) {
        registrations_[events.at(event)].set_check(p, check);
        registrations_[events.at(event)].data = data;
    }

#if defined(SWARMVM_FLOOR_PUBLIC_EXAMPLE)
    // events [EV_a, EV_u]; state 0 --EV_a--> 1 --EV_u--> 0; EV_a controllable.
    virtual void run_step() {
        if (check(1)) state_ = 0;
        if (state_ == 0) {   // EV_a, the one enabled: drawn for all that, as published
            rng_.next();
            state_ = 1;
            act(0);
        }
    }

private:
    inline static const std::vector<std::string> kEvents{"EV_a", "EV_u"};
    unsigned state_ = 0;
#elif defined(SWARMVM_FLOOR_PROBABILISTIC_EXAMPLE)
    // events [EV_u, EV_b, EV_a]; state 0 --EV_u--> 1, 1 --EV_b--> 1, 1 --EV_a--> 0; starts in 1.
    virtual void run_step() {
        if (check(0)) state_ = 1;
        if (state_ == 1) {   // EV_b and EV_a enabled, in file order
            const unsigned event = 1 + rng_.next() % 2;
            state_ = event == 1 ? 1 : 0;
            act(event);
        }
    }

private:
    inline static const std::vector<std::string> kEvents{"EV_u", "EV_b", "EV_a"};
    unsigned state_ = 1;
#else
#error "define SWARMVM_FLOOR_PUBLIC_EXAMPLE or SWARMVM_FLOOR_PROBABILISTIC_EXAMPLE"
#endif

public:
    virtual std::string get_current_state_string() { return "sup:[" + std::to_string(state_ + 1) + "]"; }

    std::map<std::string, std::size_t> events;

private:
    bool check(unsigned event) const {
        const swarmvm::detail::Registration& r = registrations_[event];
        return r.check(r, r.data);
    }
    void act(unsigned event) const {
        const swarmvm::detail::Registration& r = registrations_[event];
        r.act(r, r.data);
    }

    swarmvm::ArgosRng rng_;
    std::vector<swarmvm::detail::Registration> registrations_;
};

#endif  // SWARMVM_SCT_FLOOR_H
