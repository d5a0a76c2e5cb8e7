// The API differences between the two variants of swarmvm's sct.h, for
// tests/targets/argos/test_sct_switch.py. Built as it is, it registers callbacks the way its variant does
// (SWARMVM_SCT_VARIANT_MHSC defined or not), prints the state string, then registers an event the
// supervisor lacks and prints what that throws. With -DOTHER_VARIANT it also registers a
// callback the other variant's way, which must not compile.
//
//   variant_api SUPERVISOR.yaml
#include <string>

#include "sct.h"

class CController {
public:
    void Callback(void*) {}
    unsigned char Check(void*) { return 0; }
};

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    argos::CRandom::CreateCategory("argos", 1);
    SCTPub* sct = new SCTPub(argv[1]);
    CController controller;
#ifdef SWARMVM_SCT_VARIANT_MHSC
    sct->add_callback(&controller, sct->events["EV_start"], &CController::Callback, NULL, NULL);
    sct->add_callback(&controller, sct->events["EV_pressStart"], NULL, &CController::Check, NULL);
#ifdef OTHER_VARIANT
    sct->add_callback(&controller, std::string("EV_start"), &CController::Callback, NULL, NULL);
#endif
#else
    sct->add_callback(&controller, std::string("EV_start"), &CController::Callback, NULL, NULL);
    sct->add_callback(&controller, std::string("EV_pressStart"), NULL, &CController::Check, NULL);
#ifdef OTHER_VARIANT
    sct->add_callback(&controller, sct->events["EV_start"], &CController::Callback, NULL, NULL);
#endif
#endif
    sct->run_step();
    std::cout << sct->get_current_state_string() << std::endl;
    try {
#ifdef SWARMVM_SCT_VARIANT_MHSC
        sct->add_callback(&controller, sct->events["EV_typo"], &CController::Callback, NULL, NULL);
#else
        sct->add_callback(&controller, std::string("EV_typo"), &CController::Callback, NULL, NULL);
#endif
    } catch (const swarmvm::UnknownEvent& error) {
        std::cout << error.what() << std::endl;
    }
    delete sct;
    return 0;
}
