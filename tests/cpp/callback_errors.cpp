// C++ callbacks that throw (docs/semantics.md, "Callbacks that raise"): swarmvm::CallbackError
// names the event and the kind of callback, the original nested in it; a throwing check leaves
// the VM as it was before the step, a throwing action keeps its own transition; the next step
// runs normally; a throwing violation hook ends the step at the violation. Usage:
// callback_errors IMAGE.svm HOOK.svm; one line per finding, checked by
// tests/cpp/test_callback_errors_cpp.py.
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "swarmvm.hpp"

using swarmvm::CallbackError;
using swarmvm::VM;

namespace {

// What nested in a CallbackError: its message, or "?" when it is not a std::exception.
std::string nested_cause(const CallbackError& error) {
    try {
        std::rethrow_if_nested(error);
    } catch (const std::exception& cause) {
        return cause.what();
    } catch (...) {
        return "?";
    }
    return "(none)";
}

void report(const char* test, const CallbackError& error) {
    std::printf("%s event=%s kind=%s what=%s cause=%s\n", test, error.event().c_str(), error.kind().c_str(),
                error.what(), nested_cause(error).c_str());
}

bool same_vm(VM& a, VM& b) {
    swarmvm::XorShift32 ra = a.rng(), rb = b.rng();
    return a.states() == b.states() && a.violations() == b.violations() && ra.next() == rb.next();
}

// A check that throws: the step is abandoned before any transition; afterwards the VM steps
// as one that never saw the failure.
void throwing_check(const swarmvm::Image& image) {
    VM vm(image, swarmvm::Options()), reference(image, swarmvm::Options());
    bool broken = true;
    vm.set_check("EV_lowEnergy", [&broken](void*) -> bool {
        if (broken) throw std::runtime_error("sensor unplugged");
        return true;
    });
    reference.set_check("EV_lowEnergy", [](void*) { return true; });
    for (VM* m : {&vm, &reference}) m->set_check("EV_atCharger", [](void*) { return true; });
    try {
        vm.step();
        std::printf("check no-throw\n");
    } catch (const CallbackError& error) {
        report("check", error);
    }
    std::printf("check unchanged=%d\n", same_vm(vm, reference) ? 1 : 0);
    broken = false;
    const std::vector<unsigned> got = vm.step(), want = reference.step();
    std::printf("check next-step-same=%d\n", got == want && same_vm(vm, reference) ? 1 : 0);
}

// An action that throws: its own transition stays, the step ends there. Both VMs see the same
// inputs (each its own generator, drawn in the same order) until the reference fires a
// controllable event; in that step the VM's action throws.
void throwing_action(const swarmvm::Image& image, bool standard) {
    VM vm(image, swarmvm::Options()), reference(image, swarmvm::Options());
    std::uint32_t inputs[2] = {12345u, 12345u};
    for (unsigned k = 0; k < 2; ++k) {
        VM& m = k == 0 ? vm : reference;
        std::uint32_t* state = &inputs[k];
        for (unsigned e = 0; e < image.num_events; ++e) {
            if (!image.controllable.test(e)) {
                m.set_check(e, [state](void*) { return ((*state = *state * 1103515245u + 12345u) >> 24) < 77u; });
            } else if (k == 0) {
                m.set_action(e, [standard](void*) {
                    if (standard) throw std::runtime_error("motor stalled");
                    throw 42;
                });
            }
        }
    }
    for (unsigned step = 0; step < 20; ++step) {
        const std::vector<unsigned> fired = reference.step();
        if (!fired.empty() && image.controllable.test(fired.back())) {
            try {
                vm.step();
                std::printf("action no-throw\n");
            } catch (const CallbackError& error) {
                report(standard ? "action" : "other", error);
                std::printf("%s fired=%s kept-transition=%d\n", standard ? "action" : "other",
                            image.event_name(fired.back()).c_str(), same_vm(vm, reference) ? 1 : 0);
            }
            return;
        }
        if (vm.step() != fired) break;
    }
    std::printf("action no-controllable-event\n");
}

// The same checks bound in every way the API offers (a lambda to set_check, a VM::Check to
// set_check, a lambda to bind) step alike: the step calls a check through the function pointer
// made for its type or through its std::function. Rebinding replaces a check, unbinding
// (nullptr) leaves its event out of the step, load() keeps the bindings by name, and a copied VM
// steps with its own copies of the checks.
void binding_forms(const swarmvm::Image& image) {
    VM by_lambda(image), by_function(image), by_bind(image);
    std::uint32_t inputs[3] = {777u, 777u, 777u};
    for (unsigned e = 0; e < image.num_events; ++e) {
        if (image.controllable.test(e)) continue;
        std::uint32_t *a = &inputs[0], *b = &inputs[1], *c = &inputs[2];
        by_lambda.set_check(e, [](void*) { return false; });   // replaced below
        by_lambda.set_check(e, [a](void*) { return ((*a = *a * 1103515245u + 12345u) >> 24) < 77u; });
        by_function.set_check(e, VM::Check([b](void*) { return ((*b = *b * 1103515245u + 12345u) >> 24) < 77u; }));
        by_bind.bind(e, VM::Action(), [c](void*) { return ((*c = *c * 1103515245u + 12345u) >> 24) < 77u; });
    }
    bool same = true;
    for (unsigned step = 0; step < 200; ++step) {
        const std::vector<unsigned> want = by_lambda.step();
        same = same && by_function.step() == want && by_bind.step() == want;
    }
    std::printf("bindings same=%d\n", same ? 1 : 0);
    by_function.load(image);
    by_lambda.load(image);
    for (unsigned step = 0; step < 50; ++step) same = same && by_function.step() == by_lambda.step();
    std::printf("bindings after-load-same=%d\n", same ? 1 : 0);
    VM copy(by_lambda);   // its own copies of the checks: unbinding the original's leaves them
    bool fired_unbound = false;
    for (unsigned e = 0; e < image.num_events; ++e) {
        if (!image.controllable.test(e)) by_lambda.set_check(e, nullptr);
    }
    for (unsigned step = 0; step < 200; ++step) {
        for (unsigned e : by_lambda.step()) fired_unbound = fired_unbound || !image.controllable.test(e);
    }
    std::printf("bindings unbound-never-fire=%d\n", fired_unbound ? 0 : 1);
    for (unsigned step = 0; step < 50; ++step) same = same && copy.step() == by_function.step();
    std::printf("bindings copy-same=%d\n", same ? 1 : 0);
}

// A check that rebinds a check while the VM polls: refused (the poll list would lose the
// check it is about to call), reported as the check's failure; the VM is as before the step and
// steps on with the bindings it had.
void rebinding_check(const swarmvm::Image& image) {
    VM vm(image), reference(image);
    VM* target = &vm;
    vm.set_check("EV_lowEnergy", [&target](void*) {
        target->set_check("EV_atCharger", [](void*) { return false; });
        return true;
    });
    reference.set_check("EV_lowEnergy", [](void*) { return true; });
    for (VM* m : {&vm, &reference}) m->set_check("EV_atCharger", [](void*) { return true; });
    try {
        vm.step();
        std::printf("rebind no-throw\n");
    } catch (const CallbackError& error) {
        report("rebind", error);
    }
    std::printf("rebind unchanged=%d\n", same_vm(vm, reference) ? 1 : 0);
    vm.set_check("EV_lowEnergy", [](void*) { return true; });
    const std::vector<unsigned> got = vm.step(), want = reference.step();
    std::printf("rebind next-step-same=%d\n", got == want && same_vm(vm, reference) ? 1 : 0);
}

// A violation hook that throws (HOOK.svm: supervisor 0 has no move on EV_u, supervisor 1 moves
// on it): the step ends at the violation, as in Python: supervisor 1 has not moved, the
// violation is counted, EV_u's action has not run; the next step runs normally.
void throwing_hook(const swarmvm::Image& image) {
    VM vm(image);
    bool broken = true, acted = false;
    vm.on_violation([&broken](unsigned, unsigned) {
        if (broken) throw std::runtime_error("log full");
    });
    vm.set_check("EV_u", [](void*) { return true; });
    vm.set_action("EV_u", [&acted](void*) { acted = true; });
    try {
        vm.step();
        std::printf("hook no-throw\n");
    } catch (const CallbackError& error) {
        report("hook", error);
    }
    std::printf("hook states=%u,%u violations=%u acted=%d\n", unsigned(vm.states()[0]), unsigned(vm.states()[1]),
                unsigned(vm.violations()), acted ? 1 : 0);
    broken = false;
    const std::vector<unsigned> next = vm.step();
    std::printf("hook next-step=%u states=%u,%u acted=%d\n", unsigned(next.size()), unsigned(vm.states()[0]),
                unsigned(vm.states()[1]), acted ? 1 : 0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: callback_errors IMAGE.svm HOOK.svm\n");
        return 2;
    }
    const swarmvm::Image image = swarmvm::Image::load(argv[1]);
    throwing_check(image);
    throwing_action(image, true);
    throwing_action(image, false);
    binding_forms(image);
    rebinding_check(image);
    throwing_hook(swarmvm::Image::load(argv[2]));
    return 0;
}
