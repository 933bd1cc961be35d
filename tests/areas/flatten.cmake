# Issue 13 (flattening, strokes, evaluation overhead): the unchecked evaluation entry point and
# the degree-3 Horner kernel, against the checked calls and the exact MPFR oracle.
cj_add_test(test_eval_unchecked SOURCES test_eval_unchecked.c LIBS cj_test_oracle)
