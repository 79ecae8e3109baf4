/* test_utf8: the validator accepts every shortest-form scalar value and
 * refuses overlong forms, surrogates, values above U+10FFFF, stray
 * continuation bytes and truncated sequences (the negative controls). */
#include <string.h>

#include "check.h"
#include "tests.h"
#include "utf8.h"

static size_t len_of(const char *s)
{
    return utf8_sequence_len((const unsigned char *)s, strlen(s));
}

void test_utf8_sequences(void)
{
    CHECK(len_of("a") == 1);
    CHECK(len_of("\xc2\x80") == 2);         /* U+0080 */
    CHECK(len_of("\xdf\xbf") == 2);         /* U+07FF */
    CHECK(len_of("\xe0\xa0\x80") == 3);     /* U+0800 */
    CHECK(len_of("\xe2\x82\xac") == 3);     /* the euro sign */
    CHECK(len_of("\xef\xbf\xbd") == 3);     /* U+FFFD */
    CHECK(len_of("\xf0\x90\x80\x80") == 4); /* U+10000 */
    CHECK(len_of("\xf4\x8f\xbf\xbf") == 4); /* U+10FFFF */
    /* only the first sequence counts */
    CHECK(len_of("\xc3\xa9tude") == 2);

    /* negative controls */
    CHECK(len_of("\x80") == 0);             /* a continuation byte alone */
    CHECK(len_of("\xc0\xaf") == 0);         /* overlong '/' */
    CHECK(len_of("\xc1\xbf") == 0);         /* overlong */
    CHECK(len_of("\xe0\x80\xaf") == 0);     /* overlong, three bytes */
    CHECK(len_of("\xf0\x80\x80\xaf") == 0); /* overlong, four bytes */
    CHECK(len_of("\xed\xa0\x80") == 0);     /* surrogate U+D800 */
    CHECK(len_of("\xed\xbf\xbf") == 0);     /* surrogate U+DFFF */
    CHECK(len_of("\xf4\x90\x80\x80") == 0); /* U+110000 */
    CHECK(len_of("\xf5\x80\x80\x80") == 0); /* no such lead byte */
    CHECK(len_of("\xff") == 0);
    CHECK(len_of("\xe2\x82") == 0);         /* truncated by n */
    CHECK(len_of("\xe2(\xac") == 0);        /* a non-continuation inside */
    const unsigned char euro[] = {0xe2, 0x82, 0xac};
    CHECK(utf8_sequence_len(euro, 2) == 0); /* n cuts the sequence */
    CHECK(utf8_sequence_len(euro, 3) == 3);
}
