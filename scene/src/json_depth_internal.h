/* Private: telling "nested too deep" apart from a syntax error after cJSON refused a text. */
#ifndef CASTELJAU_JSON_DEPTH_INTERNAL_H
#define CASTELJAU_JSON_DEPTH_INTERNAL_H

/* The depth of [ and { nesting at `at` (strings skipped), counting from text's start. */
int cj_json_depth_at_(const char *text, const char *at);

#endif
