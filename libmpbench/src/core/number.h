/*
 * number.h - a number read from a token of text, as the library's text
 * formats (MoveIt's .scene, the planar world) write them; not part of
 * the API.
 */
#ifndef MPB_NUMBER_H
#define MPB_NUMBER_H

/*
 * 1 with the value in *v if the len characters at p are one finite
 * number (strtod()'s syntax) and nothing else; 0 if not, *v untouched.
 */
int mpb__number(const char *p, int len, double *v);

#endif /* MPB_NUMBER_H */
