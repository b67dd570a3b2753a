/* words.h - a line of a text format split at blanks (space, tab, CR,
 * vertical tab, form feed), the one way the scene and cloud readers
 * split theirs. */
#ifndef MPB_CORE_WORDS_H
#define MPB_CORE_WORDS_H

/* A word: len characters at p, inside the line (not NUL-terminated). */
typedef struct mpb__word {
    const char *p;
    int         len;
} mpb__word;

/* Split the line [b, e) into words, the first max of them into w.
 * Returns how many the line has (more than max when some did not fit). */
int mpb__split_words(const char *b, const char *e, mpb__word *w, int max);

#endif
