/*
 * robot_text.c - where a robot text's URDF ends and its SRDF begins
 * (mpb_robot_text_split(), world.h): the one rule the library, the
 * daemon and the planners share.
 */
#include <string.h>

#include "mpbench/mpbench.h"
#include "mpbench/world.h"

/* The URDF ends on the line of its root element's end tag (its first
 * "</robot" outside comments); an SRDF is there only if an element, not
 * just comments and blanks, follows. */
int mpb_robot_text_split(const char *text, size_t *urdf_len, size_t *srdf_at)
{
    if (text == NULL || urdf_len == NULL || srdf_at == NULL)
        return MPB_EINVAL;
    const char *p = text;
    *urdf_len = *srdf_at = strlen(text);
    while (*p) {
        if (strncmp(p, "<!--", 4) == 0) {
            const char *e = strstr(p + 4, "-->");
            if (!e)
                return MPB_OK;
            p = e + 3;
        } else if (strncmp(p, "</robot", 7) == 0 && (p[7] == '>' ||
                   p[7] == ' ' || p[7] == '\t' || p[7] == '\r' || p[7] == '\n')) {
            const char *e = strchr(p, '>');
            if (!e)
                return MPB_OK;
            /* The next line, or right after the tag if more follows on
             * its line. */
            const char *start = e + 1;
            while (*start == ' ' || *start == '\t' || *start == '\r')
                start++;
            start = *start == '\n' ? start + 1 : e + 1;
            *urdf_len = (size_t)(start - text);
            /* An SRDF only if an element follows, not just comments. */
            for (const char *t = start; *t; t++) {
                if (strncmp(t, "<!--", 4) == 0) {
                    const char *ce = strstr(t + 4, "-->");
                    if (!ce)
                        break;
                    t = ce + 2;
                } else if (*t == '<') {
                    *srdf_at = (size_t)(start - text);
                    return MPB_OK;
                }
            }
            return MPB_OK;
        } else {
            /* Both marks begin with '<': on to the next one. */
            p = strchr(p + 1, '<');
            if (!p)
                return MPB_OK;
        }
    }
    return MPB_OK;
}
