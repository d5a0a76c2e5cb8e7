/* The control-logic flash page (swarmvm_logic_page.h). */
#include "swarmvm_logic_page.h"

#ifdef SVM_LOGIC_PAGE_ADDRESS
#define PAGE_START ((const uint8_t *)(uintptr_t)(SVM_LOGIC_PAGE_ADDRESS))
#define PAGE_SIZE ((uint16_t)(SVM_LOGIC_PAGE_SIZE))
#else
extern const uint8_t __svm_logic_start[];
extern const uint8_t __svm_logic_end[];
#define PAGE_START (__svm_logic_start)
/* The linker's two symbols are distinct objects: their distance is taken between addresses. */
#define PAGE_SIZE ((uint16_t)((uintptr_t)__svm_logic_end - (uintptr_t)__svm_logic_start))
#endif

#define NAME_CAPACITY 48u

const uint8_t *svm_logic_page(void)
{
    return PAGE_START;
}

uint16_t svm_logic_page_size(void)
{
    return PAGE_SIZE;
}

uint16_t svm_logic_page_length(void)
{
    const uint8_t *page = svm_logic_page();
    uint16_t claimed = (uint16_t)(page[SVM_AT_LENGTH] | ((uint16_t)page[SVM_AT_LENGTH + 1u] << 8));
    return claimed >= SVM_MIN_IMAGE_SIZE && claimed <= svm_logic_page_size() ? claimed : svm_logic_page_size();
}

int svm_logic_page_validate(void)
{
    return svm_validate(svm_logic_page(), svm_logic_page_length(), SVM_SOURCE_FLASH);
}

int svm_logic_page_load(svm_vm_t *vm, const uint8_t *compiled, uint16_t compiled_length, uint8_t *to_compiled)
{
    svm_vm_t names;     /* the compiled-in image, only to look its event names up */
    char name[NAME_CAPACITY] = {0};
    uint8_t e;
    int result = svm_load_P(vm, svm_logic_page(), svm_logic_page_length());
    svm_init(&names);
    (void)svm_load_P(&names, compiled, compiled_length);
    for (e = 0; e < svm_num_events(vm); e++) {
        int own = e < svm_num_events(&names) ? (int)e : -1;
        if (svm_has_names(vm)) {
            uint8_t length = svm_event_name(vm, e, name, sizeof name);
            own = svm_event_index_n(&names, name, length < sizeof name ? length : (uint8_t)(sizeof name - 1u));
        }
        to_compiled[e] = (uint8_t)SVM_LOGIC_NO_EVENT;
        if (own >= 0) {
            to_compiled[e] = (uint8_t)own;
        }
    }
    return result;
}
