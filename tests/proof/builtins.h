/* Included in every configuration of make prove (prove.py): ACSL contracts of the GCC builtins
 * runtime_c/ calls, as GCC's manual defines them, for Eva, which knows no code for them (a
 * function without code or contract fails make prove: prove.py, UNKNOWN_FUNCTION). */
#ifndef PROOF_BUILTINS_H
#define PROOF_BUILTINS_H
/* __builtin_ctz: the number of trailing 0-bits of x, undefined for 0 (so required nonzero). */
/*@ requires nonzero: x != 0;
    assigns \result \from x;
    ensures range: 0 <= \result < 8 * sizeof(unsigned int);
    ensures lowest_set: ((x >> \result) & 1) == 1;
    ensures below_clear: (x & ((1 << \result) - 1)) == 0;
 */
int __builtin_ctz(unsigned int x);
#endif
