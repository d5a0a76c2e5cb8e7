/*
 * The control-logic flash page of a CapBot application: a table image (docs/image-format.md)
 * written to a dedicated flash page separately from the program, so that one VM binary runs
 * whichever supervisor the page holds (docs/image-format.md, "Loading from a flash page").
 *
 * Where the page is: built with -DSVM_LOGIC_PAGE_ADDRESS=<address> -DSVM_LOGIC_PAGE_SIZE=<bytes>
 * (the generated Zephyr CMakeLists.txt: 0xF3000, 4096 on the nRF52840), or else the linker
 * script's bounds __svm_logic_start / __svm_logic_end (the bare-metal QEMU build,
 * mps2_an386.ld: memory region SVM_LOGIC). `make build/capbot/<name>-logic.hex` writes a model's image
 * there (nrfjprog / west flash on the robot, QEMU's -device loader).
 *
 * At boot the application loads its compiled-in image first, then svm_logic_page_load(): a
 * page that holds no runnable image (empty, erased, damaged, wrong version, over the build's
 * SVM_MAX_* limits) is refused with its SVM_ERR_* code and the VM keeps the compiled-in logic.
 */
#ifndef SWARMVM_LOGIC_PAGE_H
#define SWARMVM_LOGIC_PAGE_H

#include <stdint.h>

#include "swarmvm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* to_compiled[] value of an event the compiled-in controller does not know. */
#define SVM_LOGIC_NO_EVENT 0xFFu

/* The page's first byte and its size in bytes. */
const uint8_t *svm_logic_page(void);
uint16_t svm_logic_page_size(void);

/* The image length the page claims (header field L), or the page size when the claim is
 * impossible (below the 18-byte minimum or past the page), which svm_validate then refuses. */
uint16_t svm_logic_page_length(void);

/* svm_validate of the page: SVM_OK when it holds an image this build can run. */
int svm_logic_page_validate(void);

/* Swap the page's image into `vm`, which runs the compiled-in image `compiled` (svm_load_P):
 * SVM_OK, or the SVM_ERR_* code with the compiled-in logic left in place. Either way
 * to_compiled[e] (SVM_MAX_EVENTS entries) becomes the compiled-in event of the running image's
 * event e, matched by name (by index for an image without names), or SVM_LOGIC_NO_EVENT: the
 * controller's dispatch is written for the compiled-in events. */
int svm_logic_page_load(svm_vm_t *vm, const uint8_t *compiled, uint16_t compiled_length, uint8_t *to_compiled);

#ifdef __cplusplus
}
#endif

#endif /* SWARMVM_LOGIC_PAGE_H */
