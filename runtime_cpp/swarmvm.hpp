// swarmvm C++ runtime, everything in one include: the table image (swarmvm_image.hpp, with the
// format's numbers of swarmvm_format.hpp), the VM (swarmvm_vm.hpp) and the compatibility layer of
// published SCT programs (swarmvm_compat.hpp). Header only, C++17, standard library only. A
// program that uses the VM alone may include swarmvm_vm.hpp instead.
#ifndef SWARMVM_HPP
#define SWARMVM_HPP

#include "swarmvm_image.hpp"
#include "swarmvm_vm.hpp"
#include "swarmvm_compat.hpp"

#endif  // SWARMVM_HPP
