// Drop-in for the OpenSwarm ARGoS controllers' <utility/sct.h>: the published SCT / SCTPub in
// the global namespace, stepping exactly as the published VM does (docs/compat.md): the file's
// event order, the choice drawn as `Uniform(CRange<UInt32>(0, 4294967295)) % n` from a generator
// of ARGoS's "argos" category. SCT("x/supervisor.yaml") loads the table image x/supervisor.svm
// that `swarmvm pack x/supervisor.yaml -o x/supervisor.svm` writes (it keeps the file's order).
// swarmvm::SCT and swarmvm::SCTPub (swarmvm.hpp) are the canonical step, without ARGoS.
#ifndef SWARMVM_SCT_H
#define SWARMVM_SCT_H

#include <string>

#include <argos3/core/utility/math/rng.h>

#include "swarmvm.hpp"
#include "swarmvm_argos.hpp"

class SCT : public swarmvm::BasicSCT<swarmvm::ArgosRng> {
public:
    explicit SCT(const std::string& yaml_path) : SCT(yaml_path, swarmvm::Step::exact) {}

protected:
    SCT(const std::string& yaml_path, swarmvm::Step step)
        : swarmvm::BasicSCT<swarmvm::ArgosRng>(yaml_path, swarmvm::Options(),
                                               swarmvm::ArgosRng(argos::CRandom::CreateRNG("argos")), step) {}
};

class SCTPub : public SCT {
public:
    explicit SCTPub(const std::string& yaml_path) : SCT(yaml_path, swarmvm::Step::exact_public_first) {}
};

#endif  // SWARMVM_SCT_H
