# embed_text.cmake - write the C file OUT defining `const char NAME[]`, the
# bytes of the file IN and a NUL: how `mpb view` carries its page template
# (tools/mpb/view_page.*). Run as cmake -DIN=... -DOUT=... -DNAME=... -P.
file(READ "${IN}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
file(WRITE "${OUT}.tmp"
  "/* Generated from ${IN} by cmake/embed_text.cmake; do not edit. */\n"
  "extern const char ${NAME}[];\n"
  "const char ${NAME}[] = {${hex}0};\n")
file(RENAME "${OUT}.tmp" "${OUT}")
