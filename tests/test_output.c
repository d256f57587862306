/* The output rules of rtp_file_write (image/file_write.h), where a file is written: the
 * catalogue (tests/bad) covers the refusals, whose folders must end unchanged. */
#include "image/file_write.h"
#include "tmpdir.h"

#include <criterion/criterion.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[64];

static void setup(void) { cr_assert(tmpdir_make(dir, sizeof dir, "output"), "cannot create a scratch folder"); }

static void teardown(void) { tmpdir_remove(dir); }

TestSuite(output, .init = setup, .fini = teardown);

static const char *in_dir(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", dir, name);
    return buf;
}

static void put_file(const char *path, const char *text, mode_t mode)
{
    FILE *f = fopen(path, "wb");
    cr_assert_not_null(f, "cannot create %s", path);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
    cr_assert_eq(chmod(path, mode), 0);
}

static void expect_contents(const char *path, const char *text)
{
    char buf[256] = "";
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot open %s", path);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    cr_expect_str_eq(buf, text);
}

Test(output, a_replaced_file_keeps_its_permission_bits)
{
    char path[128], err[256];
    put_file(in_dir(path, sizeof path, "old.ppm"), "old", 0604);
    cr_assert(rtp_file_write(path, "new", 3, err, sizeof err), "%s", err);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    cr_expect_eq(st.st_mode & 07777, 0604);
    expect_contents(path, "new");
    cr_expect_eq(tmpdir_count(dir), 1, "a temporary file was left behind");
}

Test(output, a_symbolic_link_is_followed_and_stays_a_link)
{
    char target[128], link[128], err[256];
    put_file(in_dir(target, sizeof target, "target.ppm"), "old", 0644);
    cr_assert_eq(symlink("target.ppm", in_dir(link, sizeof link, "link.ppm")), 0);
    cr_assert(rtp_file_write(link, "new", 3, err, sizeof err), "%s", err);
    struct stat st;
    cr_assert_eq(lstat(link, &st), 0);
    cr_expect(S_ISLNK(st.st_mode), "the link was replaced by a file");
    expect_contents(target, "new");
    cr_expect_eq(tmpdir_count(dir), 2);
}

/* NAME_MAX is 255: the temporary name must not be longer than the output's. */
Test(output, a_name_of_255_characters_works)
{
    char name[256], path[512], err[256];
    memset(name, 'a', 251);
    strcpy(name + 251, ".ppm");
    cr_assert(rtp_file_write(in_dir(path, sizeof path, name), "x", 1, err, sizeof err), "%s", err);
    expect_contents(path, "x");
    cr_expect_eq(tmpdir_count(dir), 1);
}

/* A file its user may not write is not replaced; root may write anything, as with '>'. */
Test(output, a_read_only_file_is_replaced_only_by_root)
{
    char path[128], err[256] = "";
    put_file(in_dir(path, sizeof path, "ro.ppm"), "old", 0444);
    bool ok = rtp_file_write(path, "new", 3, err, sizeof err);
    if (geteuid() == 0) {
        cr_expect(ok, "%s", err);
        expect_contents(path, "new");
        struct stat st;
        cr_assert_eq(stat(path, &st), 0);
        cr_expect_eq(st.st_mode & 07777, 0444);
    } else {
        cr_expect_not(ok);
        cr_expect(strstr(err, "Permission denied"), "%s", err);
        expect_contents(path, "old");
    }
}

Test(output, a_character_device_is_written_through_not_replaced)
{
    char err[256];
    cr_assert(rtp_file_write("/dev/null", "x", 1, err, sizeof err), "%s", err);
    struct stat st;
    cr_assert_eq(stat("/dev/null", &st), 0);
    cr_expect(S_ISCHR(st.st_mode));
    cr_expect_not(rtp_file_write("/dev/full", "x", 1, err, sizeof err));
    cr_expect(strstr(err, "/dev/full: cannot write: No space left on device"), "%s", err);
}

Test(output, a_fifo_with_a_reader_gets_the_bytes)
{
    char path[128], err[256];
    cr_assert_eq(mkfifo(in_dir(path, sizeof path, "out.fifo"), 0600), 0);
    int fd = open(path, O_RDONLY | O_NONBLOCK); /* the reader */
    cr_assert(fd >= 0);
    cr_assert(rtp_file_write(path, "abc", 3, err, sizeof err), "%s", err);
    char got[4] = "";
    cr_expect_eq(read(fd, got, 3), 3);
    cr_expect_arr_eq(got, "abc", 3);
    close(fd);
    struct stat st;
    cr_assert_eq(lstat(path, &st), 0);
    cr_expect(S_ISFIFO(st.st_mode), "the FIFO was replaced");
}

Test(output, dash_is_standard_output)
{
    int pipe_fd[2];
    cr_assert_eq(pipe(pipe_fd), 0);
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    dup2(pipe_fd[1], STDOUT_FILENO);
    char err[256];
    bool ok = rtp_file_write("-", "P6\n", 3, err, sizeof err);
    dup2(saved, STDOUT_FILENO);
    close(saved);
    close(pipe_fd[1]);
    cr_assert(ok, "%s", err);
    char got[4] = "";
    cr_expect_eq(read(pipe_fd[0], got, sizeof got), 3);
    cr_expect_arr_eq(got, "P6\n", 3);
    close(pipe_fd[0]);
    cr_expect_eq(tmpdir_count(dir), 0);
}
