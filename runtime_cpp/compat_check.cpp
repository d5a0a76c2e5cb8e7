// Exercises the compatibility API (SCT / SCTPub, as the OpenSwarm ARGoS controllers call it)
// and the VM's error paths; tests/conformance/test_cpp.py compares its output with the Python
// runtime's SCT driven the same way.
//
//   compat_check DIR/supervisor.yaml STEPS
//
// loads DIR/supervisor.svm (the .yaml itself need not exist), registers every event the
// published way (member functions, NULL for the missing half), and prints per step the
// actions called, get_current_state_string() and the violation count. Check of event "EV_x" at step k (from 1)
// returns (k * 7 + strlen("EV_x")) % 3 == 0. Then it prints one line per error path checked.
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "swarmvm.hpp"

using swarmvm::SCT;      // the canonical step (sct.h, the ARGoS drop-in, steps exactly)
using swarmvm::SCTPub;

namespace {

class Controller {
public:
    explicit Controller(const std::string& event) : event_(event) {}
    void Callback(void* data) { static_cast<std::vector<std::string>*>(data)->push_back(event_); }
    unsigned char Check(void*) { return static_cast<unsigned char>((step * 7 + event_.size()) % 3 == 0); }
    static unsigned step;

private:
    std::string event_;
};

unsigned Controller::step = 0;

void expect(bool ok, const std::string& what) {
    std::cout << (ok ? "ok " : "FAILED ") << what << "\n";
    if (!ok) std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) return 2;
    const std::string path = argv[1];
    std::unique_ptr<SCT> sct = std::make_unique<SCTPub>(path);   // as the published controllers hold it
    std::vector<std::unique_ptr<Controller>> controllers;
    std::vector<std::string> called;
    for (const auto& entry : sct->events) {
        controllers.push_back(std::make_unique<Controller>(entry.first));
        Controller* c = controllers.back().get();
        if (sct->vm().image().controllable.test(static_cast<unsigned>(entry.second))) {
            sct->add_callback(c, entry.first, &Controller::Callback, NULL, &called);
        } else {
            sct->add_callback(c, entry.first, NULL, &Controller::Check, NULL);
        }
    }
    const unsigned steps = static_cast<unsigned>(std::stoul(argv[2]));
    std::vector<std::vector<std::string>> first_run;
    for (Controller::step = 1; Controller::step <= steps; ++Controller::step) {
        called.clear();
        sct->run_step();
        first_run.push_back(called);
        std::string line = std::to_string(Controller::step) + " ";
        for (std::size_t i = 0; i < called.size(); ++i) line += (i ? "," : "") + called[i];
        std::cout << line << (called.empty() ? "-" : "") << " " << sct->get_current_state_string() << " "
                  << sct->vm().violations() << "\n";
    }

    Controller stray("EV_noSuchEvent");
    try {
        sct->add_callback(&stray, std::string("EV_noSuchEvent"), &Controller::Callback, NULL, NULL);
        expect(false, "unknown event refused");
    } catch (const swarmvm::UnknownEvent& ex) {
        expect(std::string(ex.what()).find("EV_noSuchEvent") != std::string::npos, "unknown event refused with its name");
    }
    try {
        swarmvm::parse_policy("learned");
        expect(false, "learned policy refused");
    } catch (const std::invalid_argument&) {
        expect(true, "learned policy refused");
    }

    // A refused image leaves the VM with its previous logic; a good one swaps and resets.
    swarmvm::VM& vm = sct->vm();
    std::vector<std::uint8_t> bad = vm.image().raw;
    bad[bad.size() / 2] ^= 0x5A;
    const std::vector<std::uint16_t> before = vm.states();
    try {
        vm.load(swarmvm::Image::parse(bad.data(), bad.size()));
        expect(false, "corrupted image refused");
    } catch (const swarmvm::ImageError& ex) {
        expect(std::string(ex.what()).find("checksum") != std::string::npos && vm.states() == before,
               "corrupted image refused, previous logic kept");
    }
    const std::vector<std::uint8_t> good = vm.image().raw;
    vm.load(swarmvm::Image::parse(good.data(), good.size()));
    bool initial = true;
    for (std::uint16_t state : vm.states()) initial = initial && state == 0;
    expect(initial, "swapped image restarts from the initial states");
    bool same = true;
    for (Controller::step = 1; Controller::step <= steps; ++Controller::step) {
        called.clear();
        sct->run_step();
        same = same && called == first_run[Controller::step - 1];
    }
    expect(same, "callbacks rebound by name after the swap: the run repeats");

    // The core API: member functions through swarmvm::member, the violation hook.
    swarmvm::VM core(vm.image());
    std::vector<Controller> owners;
    for (unsigned e = 0; e < core.image().num_events; ++e) owners.emplace_back(core.image().event_name(e));
    for (unsigned e = 0; e < core.image().num_events; ++e) {
        if (core.image().controllable.test(e)) {
            core.bind(e, swarmvm::member(&owners[e], &Controller::Callback), nullptr, &called);
        } else {
            core.set_check(e, swarmvm::member(&owners[e], &Controller::Check));
        }
    }
    unsigned hooked = 0;
    core.on_violation([&hooked](unsigned, unsigned) { ++hooked; });
    same = true;
    for (Controller::step = 1; Controller::step <= steps; ++Controller::step) {
        called.clear();
        core.step();
        same = same && called == first_run[Controller::step - 1];
    }
    expect(same && hooked == core.violations(), "member callbacks and the violation hook on the core VM");
    return 0;
}
