/* The nesting depth where cJSON stopped: cJSON refuses documents nested deeper than
 * CJSON_NESTING_LIMIT with the same failure as a syntax error, so the readers measure it to say
 * which it was. */
#include "json_depth_internal.h"

int cj_json_depth_at_(const char *text, const char *at) {
    int depth = 0, max = 0, in_string = 0;
    for (const char *s = text; *s && (!at || s <= at); ++s) {
        if (in_string) {
            if (*s == '\\' && s[1])
                ++s;
            else if (*s == '"')
                in_string = 0;
            continue;
        }
        if (*s == '"')
            in_string = 1;
        else if (*s == '[' || *s == '{')
            max = ++depth > max ? depth : max;
        else if (*s == ']' || *s == '}')
            --depth;
    }
    return max;
}
