/* utf8: the one UTF-8 validator, for the scene parser's comments and the
 * JSON writer's strings. */
#ifndef PM_UTF8_H
#define PM_UTF8_H

#include <stddef.h>

/* Length (1-4) of the valid UTF-8 sequence at s, reading at most n >= 1
 * bytes; 0 if the bytes there are not valid UTF-8. */
size_t utf8_sequence_len(const unsigned char *s, size_t n);

#endif
