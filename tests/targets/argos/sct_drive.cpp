// Drives an SCT/SCTPub through the published API only, for tests/targets/argos/test_sct_exact_cpp.py:
// built once against the published sct.cpp (the oracle) and once against swarmvm's sct.h, the
// two outputs must be equal. Every event gets a callback the published way (member functions);
// checks have side effects (they draw from the controller's own generator and clear flags that
// other checks read); each step prints the calls made and get_current_state_string(). REGISTER
// picks how events are registered:
//   both     every event an action and a check (add_callback's third form), once;
//   again    the same, then each event registered again: every other one with a check only
//            (a controllable one too: the published VM keeps the check and never calls it), the
//            others with an action only, which replace what the first registration gave;
//   throws   as both, and a check sometimes throws argos::CARGoSException, which the driver
//            catches as such, prints, and goes on stepping.
//
//   sct_drive SUPERVISOR.yaml pub|plain STEPS SEED [both|again|throws]
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <argos3/core/utility/configuration/argos_exception.h>
#include <argos3/core/utility/math/rng.h>

#include "sct.h"

class Controller {
public:
    Controller(SCT& sct, const std::string& mode) : sct_(sct), throws_(mode == "throws") {
        for (const auto& entry : sct.events) names_.push_back(entry.first);
        slots_.resize(names_.size());
        for (std::size_t k = 0; k < names_.size(); ++k) {
            slots_[k] = {this, k};
            // The same member functions for every event: a check and an action; each SCT uses
            // the half that fits the event's kind.
            sct.add_callback(this, names_[k], &Controller::Act, &Controller::Check, &slots_[k]);
        }
        if (mode != "again") return;
        for (std::size_t k = 0; k < names_.size(); ++k) {
            if (k % 2 == 0) {
                sct.add_callback(this, names_[k], NULL, &Controller::Check, &slots_[k]);
            } else {
                sct.add_callback(this, names_[k], &Controller::Act, NULL, &slots_[k]);
            }
        }
    }

    void Step() {
        calls_.clear();
        try {
            sct_.run_step();
        } catch (argos::CARGoSException& ex) {   // as a published controller would catch it
            calls_ += std::string(" caught:") + ex.what();
        }
        std::cout << sct_.get_current_state_string() << " |" << calls_ << "\n";
    }

private:
    struct Slot {
        Controller* self;
        std::size_t name;
    };

    std::uint32_t Draw() {   // the controller's own generator (xorshift32), not the SCT's
        state_ ^= state_ << 13;
        state_ ^= state_ >> 17;
        state_ ^= state_ << 5;
        return state_;
    }

    unsigned char Check(void* data) {
        const Slot* slot = static_cast<Slot*>(data);
        calls_ += " c:" + names_[slot->name];
        const bool seen = flag_ == slot->name;
        if (seen) flag_ = SIZE_MAX;                       // clears what another callback set
        const std::uint32_t draw = Draw();
        if (throws_ && draw % 23u == 0) throw argos::CARGoSException("check of " + names_[slot->name] + " failed");
        return static_cast<unsigned char>(seen || draw % 10u < 3u);
    }

    void Act(void* data) {
        const Slot* slot = static_cast<Slot*>(data);
        calls_ += " a:" + names_[slot->name];
        flag_ = Draw() % names_.size();                    // read by a later check
    }

    SCT& sct_;
    bool throws_;
    std::vector<std::string> names_;
    std::vector<Slot> slots_;
    std::string calls_;
    std::size_t flag_ = SIZE_MAX;
    std::uint32_t state_ = 2463534242u;
};

int main(int argc, char** argv) {
    if (argc != 5 && argc != 6) {
        std::cerr << "usage: sct_drive SUPERVISOR.yaml pub|plain STEPS SEED [both|again|throws]\n";
        return 2;
    }
    argos::CRandom::CreateCategory("argos", static_cast<argos::UInt32>(std::strtoul(argv[4], nullptr, 10)));
    std::unique_ptr<SCT> sct;
    if (std::string(argv[2]) == "pub") {
        sct = std::make_unique<SCTPub>(argv[1]);
    } else {
        sct = std::make_unique<SCT>(argv[1]);
    }
    Controller controller(*sct, argc == 6 ? argv[5] : "both");
    for (long k = std::strtol(argv[3], nullptr, 10); k > 0; --k) controller.Step();
    return 0;
}
