/* `rtk verify`: manifests written and checked, a differing hash, a scene that cannot be
 * rendered, malformed manifests, and the JUnit report. */
#include "capture.h"
#include "cli/exit_codes.h"
#include "cli/verify_cmd.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char dir[64], manifest[128], junit[128], spaced[160];

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    static char text[8192];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    return text;
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    cr_assert(f, "cannot write %s", path);
    fputs(text, f);
    fclose(f);
}

static int verify(char **out, int argc, ...)
{
    char *argv[16] = {"verify"};
    va_list ap;
    va_start(ap, argc);
    for (int i = 1; i < argc; i++) argv[i] = va_arg(ap, char *);
    va_end(ap);
    return capture_stdout(rtp_cmd_verify, argc, argv, out);
}

static void setup(void)
{
    cr_assert(tmpdir_make(dir, sizeof dir, "verify"), "cannot create a scratch folder");
    snprintf(manifest, sizeof manifest, "%s/hashes.txt", dir);
    snprintf(junit, sizeof junit, "%s/results.xml", dir);
    snprintf(spaced, sizeof spaced, "%s/a scene.yaml", dir);
    cr_redirect_stderr();
}

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(verify, .init = setup, .fini = teardown);

Test(verify, a_written_manifest_checks_ok)
{
    char *out = NULL;
    cr_assert_eq(verify(&out, 9, "--write", manifest, "scenes/demo.yaml", "scenes/opaque_shadows.yaml", "--width", "24",
                        "--height", "24"),
                 RTP_EXIT_OK);
    free(out);
    const char *text = read_all(manifest);
    cr_assert(text);
    cr_expect(strstr(text, "  scenes/demo.yaml --width 24 --height 24\n") != NULL, "%s", text);
    cr_expect_eq(text[64], ' ', "%s", text);
    cr_assert_eq(verify(&out, 4, manifest, "--junit", junit), RTP_EXIT_OK);
    cr_expect(strstr(out, "scenes/demo.yaml: OK\nscenes/opaque_shadows.yaml: OK\n") != NULL, "%s", out);
    free(out);
    const char *xml = read_all(junit);
    cr_expect(strstr(xml, "tests=\"2\" failures=\"0\" errors=\"0\"") != NULL, "%s", xml);
}

Test(verify, a_differing_hash_fails_with_the_hash_it_got)
{
    char *out = NULL;
    cr_assert_eq(verify(&out, 8, "--write", manifest, "scenes/demo.yaml", "--width", "16", "--height", "16"),
                 RTP_EXIT_OK);
    free(out);
    char *text = read_all(manifest);
    char got[65];
    memcpy(got, text, 64);
    got[64] = '\0';
    text[0] = text[0] == '0' ? '1' : '0';
    write_text(manifest, text);
    cr_assert_eq(verify(&out, 4, manifest, "--junit", junit), RTP_EXIT_THRESHOLD);
    char want[128];
    snprintf(want, sizeof want, "scenes/demo.yaml: FAILED (got %s)\n", got);
    cr_expect(strstr(out, want) != NULL, "%s", out);
    free(out);
    cr_expect(strstr(read_all(junit), "<failure message=\"render hash differs\">") != NULL);
}

Test(verify, a_scene_that_cannot_render_fails_and_is_an_error_in_junit)
{
    write_text(manifest, "# a comment, then a blank line\n\n"
                         "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef  no/such.yaml\n");
    char *out = NULL;
    cr_assert_eq(verify(&out, 4, manifest, "--junit", junit), RTP_EXIT_THRESHOLD);
    cr_expect(strstr(out, "no/such.yaml: FAILED (") != NULL, "%s", out);
    free(out);
    cr_expect(strstr(read_all(junit), "errors=\"1\"") != NULL);
}

/* A scene path with markup, a control character and a byte that is not UTF-8: the report
 * shows them escaped and holds only valid UTF-8. */
Test(verify, the_junit_report_stays_well_formed_for_any_scene_name)
{
    write_text(manifest, "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef  "
                         "no/<such>&\x01\xff\xc3\xa9.yaml\n");
    char *out = NULL;
    cr_assert_eq(verify(&out, 4, manifest, "--junit", junit), RTP_EXIT_THRESHOLD);
    free(out);
    const char *xml = read_all(junit);
    cr_expect(strstr(xml, "no/&lt;such&gt;&amp;\\x01\\xff\xc3\xa9.yaml") != NULL, "%s", xml);
    for (const unsigned char *p = (const unsigned char *)xml; *p; p++)
        cr_expect(*p >= 0x20 || *p == '\n', "a raw control byte 0x%02x in the report", *p);
    cr_expect(strchr(xml, '\xff') == NULL, "a raw 0xff byte in the report");
}

Test(verify, a_quoted_scene_path_may_hold_spaces)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "cp scenes/demo.yaml '%s'", spaced);
    cr_assert_eq(system(cmd), 0);
    char *out = NULL;
    cr_assert_eq(verify(&out, 8, "--write", manifest, spaced, "--width", "8", "--height", "8"), RTP_EXIT_OK);
    free(out);
    cr_expect(strstr(read_all(manifest), "  \"") != NULL);
    cr_assert_eq(verify(&out, 2, manifest), RTP_EXIT_OK);
    cr_expect(strstr(out, "a scene.yaml: OK") != NULL, "%s", out);
    free(out);
}

Test(verify, malformed_manifests_and_arguments_are_refused)
{
    char *out = NULL;
    write_text(manifest, "0123  scene.yaml\n");
    cr_expect_eq(verify(&out, 2, manifest), RTP_EXIT_INPUT);
    free(out);
    write_text(manifest, "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef  \"open.yaml\n");
    cr_expect_eq(verify(&out, 2, manifest), RTP_EXIT_INPUT);
    free(out);
    write_text(manifest, "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef  s.yaml --width 0\n");
    cr_expect_eq(verify(&out, 2, manifest), RTP_EXIT_THRESHOLD, "a bad option is that line's failure");
    free(out);
    cr_expect_eq(verify(&out, 2, "no/such/manifest.txt"), RTP_EXIT_INPUT);
    free(out);
    cr_expect_eq(verify(&out, 1), RTP_EXIT_USAGE);
    free(out);
    cr_expect_eq(verify(&out, 6, "--write", manifest, "scenes/demo.yaml", "--junit", junit), RTP_EXIT_USAGE);
    free(out);
    cr_expect_eq(verify(&out, 3, manifest, "--width"), RTP_EXIT_USAGE);
    free(out);
}
