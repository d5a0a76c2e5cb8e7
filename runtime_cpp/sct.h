// Drop-in for the OpenSwarm ARGoS controllers' <utility/sct.h>: the published SCT / SCTPub in
// the global namespace, stepping exactly as the published VM does (docs/compat.md): the file's
// event order, the choice drawn as `Uniform(CRange<UInt32>(0, 4294967295)) % n` from a generator
// of ARGoS's "argos" category. SCT("x/supervisor.yaml") loads the table image x/supervisor.svm
// that `swarmvm pack x/supervisor.yaml -o x/supervisor.svm` writes (it keeps the file's order).
// swarmvm::SCT and swarmvm::SCTPub (swarmvm.hpp) are the canonical step, without ARGoS.
//
// Two variants of the published header exist; this one is either, by one define:
//   default                    callbacks by event name, states printed from 1 ("sup:[4,1,3]")
//   SWARMVM_SCT_VARIANT_MHSC   the multi-human swarm control variant (sct_mhsc.hpp): callbacks
//                              by event index, states printed from 0 ("sup:[3,0,2]")
// Calling the other variant's add_callback fails to compile with a message naming the define.
#ifndef SWARMVM_SCT_H
#define SWARMVM_SCT_H

// The standard headers the published sct.h includes: its controllers use std::queue, std::map,
// std::function, std::cout, exit() and time() without including them.
#include <stdlib.h>
#include <ctime>
#include <functional>
#include <iostream>
#include <map>
#include <queue>
#include <string>
#include <type_traits>

#include <argos3/core/utility/math/rng.h>

#include "swarmvm.hpp"
#include "swarmvm_argos.hpp"
#ifdef SWARMVM_SCT_VARIANT_MHSC
#include "sct_mhsc.hpp"
#endif

namespace swarmvm {

// What both variants share: the exact step, drawing from ARGoS's "argos" generator.
class ArgosSCT : public BasicSCT<ArgosRng> {
protected:
    ArgosSCT(const std::string& yaml_path, Step step)
        : BasicSCT<ArgosRng>(yaml_path, Options(), ArgosRng(argos::CRandom::CreateRNG("argos")), step) {}
};

// The default variant: callbacks registered by event name.
class NamedSCT : public ArgosSCT {
public:
    using ArgosSCT::add_callback;
    template <class C, class I, class A, class K, std::enable_if_t<std::is_integral<I>::value, int> = 0>
    void add_callback(C*, I, A, K, void*) {
        static_assert(!std::is_integral<I>::value,
                      "sct.h: callbacks registered by event index are the API of the multi-human swarm control "
                      "variant; build with -DSWARMVM_SCT_VARIANT_MHSC (docs/compat.md)");
    }

protected:
    using ArgosSCT::ArgosSCT;
};

#ifdef SWARMVM_SCT_VARIANT_MHSC
using PublishedSCT = MhscSCT<ArgosSCT>;
#else
using PublishedSCT = NamedSCT;
#endif

}  // namespace swarmvm

class SCT : public swarmvm::PublishedSCT {
public:
    explicit SCT(const std::string& yaml_path) : SCT(yaml_path, swarmvm::Step::exact) {}

protected:
    SCT(const std::string& yaml_path, swarmvm::Step step) : swarmvm::PublishedSCT(yaml_path, step) {}
};

class SCTPub : public SCT {
public:
    explicit SCTPub(const std::string& yaml_path) : SCT(yaml_path, swarmvm::Step::exact_public_first) {}
};

#endif  // SWARMVM_SCT_H
