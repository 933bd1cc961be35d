# Issue 13 (flattening, strokes, evaluation overhead): the unchecked evaluation entry point and
# the degree-3 Horner kernel, against the checked calls and the exact MPFR oracle.
cj_add_test(test_eval_unchecked SOURCES test_eval_unchecked.c LIBS cj_test_oracle)

# Issue 20: the planar fast path's segments placed up front and certified; counts against the
# continuous optimum, bounds against long-double samples.
cj_add_test(test_flatten_count SOURCES flatten_count.c)
