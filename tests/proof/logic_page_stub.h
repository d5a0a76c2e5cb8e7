/* Included before runtime_c/swarmvm_logic_page.c by the logic-page configuration (prove.py): the
 * page's address, as the CapBot's CMakeLists gives SVM_LOGIC_PAGE_ADDRESS a flash address, is
 * here the harness's array. */
#include <stdint.h>
extern uint8_t proof_page[];
