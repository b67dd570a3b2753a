/*
 * test_note_messages.h - the one line that makes lcmtypes' test_note_t
 * (tests/support/lcmtypes/test_note_t.lcm) a message of the net layer
 * test_messages builds: force-included before its copy of
 * libmpbench/src/net/{wire,receive,auth}.c (tests/CMakeLists.txt), as a
 * new message's line would be added to MPB_MESSAGES (mpbench/messages.h).
 */
#define MPB_MESSAGES_EXTRA(X) X(TEST_NOTE, note, test_note_t, "MPB_TEST_NOTE")
