// The C++ VM's two ways of stepping agree (runtime_cpp/swarmvm.hpp): a VM whose callbacks are
// all checks steps by composed state; the same VM with an action on every event and a violation
// hook steps an input with an action, or a violation, the general way. Both run the same
// pseudo-random inputs under every option; the program prints one line per option set:
//   INPUTS CONTROL POLICY same=S hook=H actions=A states=T
// S: both VMs fired the same events and reached the same states and violation counts at every
// step; H: the hook was called once per violation counted; A: the actions ran once per fired
// event, in the order fired; T: every action saw its own event's transition applied (checked
// for the step's last event, whose transition ends the step). A last line "set-in-check A":
// A, actions that a check sets while the VM polls run in that same step, once per fired event.
// Usage: step_paths IMAGE.svm
#include <cstdint>
#include <cstdio>
#include <vector>

#include "swarmvm.hpp"

namespace {

struct Run {
    swarmvm::VM vm;
    std::uint32_t inputs = 12345u;   // the checks' pseudo-random values (an LCG: not the VM's generator)
};

// Binds every uncontrollable event's check to a pseudo-random value, one in four true.
void bind_inputs(Run& run) {
    const swarmvm::Image& image = run.vm.image();
    for (unsigned e = 0; e < image.num_events; ++e) {
        if (image.controllable.test(e)) continue;
        std::uint32_t* state = &run.inputs;
        run.vm.set_check(e, [state](void*) { return ((*state = *state * 1103515245u + 12345u) >> 24) < 64u; });
    }
}

void compare(const swarmvm::Image& image, swarmvm::Inputs inputs, swarmvm::Control control, swarmvm::Policy policy) {
    swarmvm::Options options;
    options.inputs = inputs;
    options.control = control;
    options.policy = policy;
    options.seed = 42;
    Run plain{swarmvm::VM(image, options)}, hooked{swarmvm::VM(image, options)};
    bind_inputs(plain);
    bind_inputs(hooked);
    std::uint32_t hook_calls = 0;
    std::vector<unsigned> acted;
    std::vector<std::uint16_t> seen;   // the states the last action of a step saw
    hooked.vm.on_violation([&hook_calls](unsigned, unsigned) { ++hook_calls; });
    for (unsigned e = 0; e < image.num_events; ++e) {
        hooked.vm.set_action(e, [&acted, &seen, &hooked, e](void*) {
            acted.push_back(e);
            seen = hooked.vm.states();
        });
    }
    bool same = true, actions = true, states = true;
    for (unsigned step = 0; step < 400; ++step) {
        acted.clear();
        const std::vector<unsigned> want = plain.vm.step();
        const std::vector<unsigned> got = hooked.vm.step();
        same = same && got == want && plain.vm.states() == hooked.vm.states() &&
               plain.vm.violations() == hooked.vm.violations();
        actions = actions && acted == got;
        states = states && (got.empty() || seen == hooked.vm.states());
    }
    static const char* const kInputs[] = {"level", "edge"};
    static const char* const kControl[] = {"after-inputs", "if-quiet"};
    static const char* const kPolicy[] = {"uniform", "first", "weighted"};
    std::printf("%s %s %s same=%d hook=%d actions=%d states=%d\n", kInputs[static_cast<int>(inputs)],
                kControl[static_cast<int>(control)], kPolicy[static_cast<int>(policy)], same ? 1 : 0,
                hook_calls == hooked.vm.violations() ? 1 : 0, actions ? 1 : 0, states ? 1 : 0);
}

// A check sets an action on every event while the VM polls, from the first step on: the
// actions run in that step already, for every event it fires (the general step's order).
void action_set_by_check(const swarmvm::Image& image) {
    Run run{swarmvm::VM(image)};
    bind_inputs(run);
    std::vector<unsigned> acted;
    bool set = false;
    unsigned first_input = 0;
    while (image.controllable.test(first_input)) ++first_input;
    run.vm.set_check(first_input, [&run, &acted, &set, &image](void*) {
        for (unsigned e = 0; !set && e < image.num_events; ++e) {
            run.vm.set_action(e, [&acted, e](void*) { acted.push_back(e); });
        }
        set = true;
        return ((run.inputs = run.inputs * 1103515245u + 12345u) >> 24) < 64u;
    });
    bool same = true;
    for (unsigned step = 0; step < 50; ++step) {
        acted.clear();
        same = same && run.vm.step() == acted;
    }
    std::printf("set-in-check %d\n", same ? 1 : 0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: step_paths IMAGE.svm\n");
        return 2;
    }
    const swarmvm::Image image = swarmvm::Image::load(argv[1]);
    for (swarmvm::Inputs inputs : {swarmvm::Inputs::level, swarmvm::Inputs::edge}) {
        for (swarmvm::Control control : {swarmvm::Control::after_inputs, swarmvm::Control::if_quiet}) {
            for (swarmvm::Policy policy : {swarmvm::Policy::uniform, swarmvm::Policy::first, swarmvm::Policy::weighted}) {
                compare(image, inputs, control, policy);
            }
        }
    }
    action_set_by_check(image);
    return 0;
}
