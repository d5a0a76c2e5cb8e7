/*
 * The learned policy kept in a store (runtime_c/swarmvm_learn_store.h), on a host with a
 * simulated EEPROM. Test code only. keeper_data.h gives the table image (KEEPER_IMAGE), the
 * event to reward (KEEPER_GOOD) and the cadence (KEEPER_EVERY). Lines:
 *   "begin R"           svl_keeper_begin's result on an erased medium (0: initial parameters)
 *   "save U"            a save, after U credited rewards in all (the policy's updates)
 *   "quiet N"           after a save (svl_keeper_save), saves during rewards equal to the
 *                       baseline (nothing learned): N
 *   "restart R SAME"    begin again on the medium: R (1: loaded) and whether the preferences
 *                       equal those of the last save (1)
 *   "damaged R ZERO"    begin with both slots damaged: R (0) and whether all preferences are 0
 */
#include <stdio.h>
#include <string.h>

#include "swarmvm_learn_store.h"
#include "keeper_data.h"

#define THETA_CAP 64u
static uint8_t cells[1024];
static uint8_t fired;

static uint8_t cell_read(void *ctx, uint16_t address)
{
    (void)ctx;
    return cells[address];
}

static int cell_write(void *ctx, uint16_t address, const uint8_t *data, uint16_t length)
{
    (void)ctx;
    memcpy(&cells[address], data, length);
    return 0;
}

static uint8_t dispatch(svm_vm_t *vm, uint8_t event, uint8_t op)
{
    (void)vm;
    if (op == SVM_OP_ACTION) {
        fired = event;
    }
    return 0;
}

typedef struct {
    svm_vm_t vm;
    svl_policy_t policy;
    svl_keeper_t keeper;
    int32_t theta[THETA_CAP];
    uint32_t words[SVL_KEEPER_WORDS(THETA_CAP)];
} robot_t;

static int boot(robot_t *r, const svm_store_t *store)
{
    memset(r, 0, sizeof *r);
    svm_init(&r->vm);
    svm_set_dispatch(&r->vm, dispatch);
    if (svm_load(&r->vm, keeper_image, sizeof keeper_image) != SVM_OK) {
        return -2;
    }
    return svl_keeper_begin(&r->keeper, &r->policy, &r->vm, 7u, r->theta, THETA_CAP, r->words, store, KEEPER_EVERY);
}

static robot_t robot, again;

int main(void)
{
    svm_store_t store;
    int32_t saved[THETA_CAP];
    uint16_t step, i;
    uint32_t saves;
    int zero = 1, result;
    store.medium.read = cell_read;
    store.medium.write = cell_write;
    store.medium.erase = 0;
    store.medium.ctx = 0;
    store.medium.block = 1;
    store.base = 16;
    store.slot_size = (uint16_t)SVM_STORE_SLOT_BYTES(SVL_KEEPER_RECORD_BYTES(THETA_CAP), 1u);
    memset(cells, 0xFF, sizeof cells);
    printf("begin %d\n", boot(&robot, &store));
    for (step = 0; step < 10u * KEEPER_EVERY; step++) {
        fired = 0xFF;
        (void)svm_step(&robot.vm);
        if (svl_keeper_reward(&robot.keeper, fired == KEEPER_GOOD ? SVL_Q16(4.0) : SVL_Q16(-1.0)) == 1) {
            printf("save %lu\n", (unsigned long)robot.policy.updates);
            memcpy(saved, robot.theta, sizeof saved);
        }
    }
    (void)svl_keeper_save(&robot.keeper);             /* a planned shutdown: since and moved from 0 */
    memcpy(saved, robot.theta, sizeof saved);
    saves = robot.keeper.saves;
    for (step = 0; step < 4u * KEEPER_EVERY; step++) {
        (void)svm_step(&robot.vm);
        (void)svl_keeper_reward(&robot.keeper, robot.policy.baseline);
    }
    printf("quiet %lu\n", (unsigned long)(robot.keeper.saves - saves));
    result = boot(&again, &store);
    printf("restart %d %d\n", result, memcmp(saved, again.theta, sizeof saved) == 0);
    cells[store.base + 20u] ^= 0x01u;
    cells[store.base + store.slot_size + 20u] ^= 0x01u;
    result = boot(&again, &store);
    printf("damaged %d", result);
    for (i = 0; i < THETA_CAP; i++) {
        zero = zero && again.theta[i] == 0;
    }
    printf(" %d\n", zero);
    return 0;
}
