// Drop-in for the OpenSwarm controllers' <utility/sct.h>: the published SCT / SCTPub names
// in the global namespace, implemented by the swarmvm VM (swarmvm.hpp). SCT("x/supervisor.yaml")
// loads the table image x/supervisor.svm written by `swarmvm pack` or `swarmvm gen`.
#ifndef SWARMVM_SCT_H
#define SWARMVM_SCT_H

#include "swarmvm.hpp"

using swarmvm::SCT;
using swarmvm::SCTPub;

#endif  // SWARMVM_SCT_H
