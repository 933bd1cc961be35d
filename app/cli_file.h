/* Private to the casteljau tool: output files that are complete or absent. */
#ifndef CASTELJAU_APP_CLI_FILE_H
#define CASTELJAU_APP_CLI_FILE_H

#include <stddef.h>
#include <stdio.h>

typedef struct cli_file {
    FILE *fp; /* write here */
    char *tmp;
    const char *path;
} cli_file;

/* Creates the temporary file beside `path` (which must outlive f). 0, or -1 with a reason. */
int cli_file_open(cli_file *f, const char *path, char *why, size_t why_size);

/* Checks every write (ferror), flushes, fsyncs and closes, then renames onto the path. On any
 * failure the temporary file is removed, the path keeps its old content, and -1 is returned
 * with a reason naming the path ("No space left on device"). */
int cli_file_commit(cli_file *f, char *why, size_t why_size);

/* Closes and removes the temporary file (after an error of the caller's own). */
void cli_file_abandon(cli_file *f);

#endif
