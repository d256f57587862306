/* One-line messages (platform/cli/message.h): control characters and invalid UTF-8 are
 * escaped, printable UTF-8 is kept. */
#include "cli/message.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static void expect_escaped(const char *in, const char *want)
{
    char out[256];
    rtp_message_escape(in, out, sizeof out);
    cr_expect_str_eq(out, want, "escaping '%s'", in);
}

Test(message, controls_are_escaped)
{
    expect_escaped("a\nb", "a\\nb");
    expect_escaped("tab\there\r", "tab\\there\\r");
    expect_escaped("\x1b[31mred\x1b[0m", "\\x1b[31mred\\x1b[0m");
    expect_escaped("del\x7f", "del\\x7f");
    expect_escaped("bell\a", "bell\\a");
}

Test(message, printable_utf8_is_kept_and_c1_and_broken_bytes_escaped)
{
    expect_escaped("caf\xc3\xa9 \xe2\x82\xac", "caf\xc3\xa9 \xe2\x82\xac"); /* café € */
    expect_escaped("csi\xc2\x9b", "csi\\xc2\\x9b");                         /* U+009B, a C1 control */
    expect_escaped("bad\xff", "bad\\xff");
    expect_escaped("cut\xe2\x82", "cut\\xe2\\x82");   /* a sequence cut short */
    expect_escaped("long\xc0\xaf", "long\\xc0\\xaf"); /* overlong '/' */
}

Test(message, output_is_cut_to_fit)
{
    char out[6];
    rtp_message_escape("a\nbcdef", out, sizeof out);
    cr_expect_str_eq(out, "a\\nbc");
}

Test(message, a_message_is_one_line_on_stderr)
{
    int fds[2];
    cr_assert_eq(pipe(fds), 0);
    fflush(stderr);
    int saved = dup(STDERR_FILENO);
    dup2(fds[1], STDERR_FILENO);
    rtp_message("render", "%s: cannot read '%s'", "scene.yaml", "x\ny.ply");
    dup2(saved, STDERR_FILENO);
    close(saved);
    close(fds[1]);
    char got[256] = "";
    ssize_t n = read(fds[0], got, sizeof got - 1);
    close(fds[0]);
    cr_assert(n > 0);
    cr_expect_str_eq(got, "rtk render: scene.yaml: cannot read 'x\\ny.ply'\n");
}
