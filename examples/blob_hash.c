/* Renders the scene blob linked into this program (made by `rtk pack`) and prints its
 * render hash, with the kernel alone: no C library at all. The program brings its entry
 * point and a write to standard output as Linux system calls (x86-64 and aarch64); the
 * three functions the kernel may call (memcpy, memset, memmove) come from the bare-metal
 * board's targets/cortex-m/memory.c, plain C that serves any freestanding program.
 * Build: see examples.mk. */
#include <rtk.h>

#if !defined(__linux__) || !(defined(__x86_64__) || defined(__aarch64__))
#error "blob_hash: this example's entry point and write are for Linux on x86-64 or aarch64"
#endif

/* The blob, linked in with `ld -r -b binary scene.rtscene`. */
extern const uint8_t _binary_scene_rtscene_start[], _binary_scene_rtscene_end[];

/* The arena the scene is built in, and the largest image this example renders. */
static uint8_t memory[64 << 20];
#define MAX_PIXELS (512 * 512)
static uint8_t rgb[MAX_PIXELS * 3];

static long sys_write(int fd, const void *buf, size_t n)
{
    long ret;
#if defined(__x86_64__)
    __asm__ volatile("syscall" : "=a"(ret) : "a"(1), "D"(fd), "S"(buf), "d"(n) : "rcx", "r11", "memory");
#else
    register long x0 __asm__("x0") = fd, x1 __asm__("x1") = (long)buf, x2 __asm__("x2") = (long)n;
    register long x8 __asm__("x8") = 64;
    __asm__ volatile("svc 0" : "+r"(x0) : "r"(x1), "r"(x2), "r"(x8) : "memory");
    ret = x0;
#endif
    return ret;
}

static size_t length(const char *s)
{
    size_t n = 0;
    while (s[n]) n++;
    return n;
}

static int say(const char *line)
{
    sys_write(1, line, length(line));
    return sys_write(1, "\n", 1) == 1 ? 0 : 4;
}

int blob_hash_main(void);
int blob_hash_main(void)
{
    const rtk_scene *scene;
    size_t needed;
    size_t size = (size_t)(_binary_scene_rtscene_end - _binary_scene_rtscene_start);
    rtk_status st = rtk_scene_from_blob(_binary_scene_rtscene_start, size, memory, sizeof memory, &scene, &needed);
    if (st != RTK_OK) return say(rtk_status_name(st)) + 3;
    uint32_t w, h;
    rtk_scene_size(scene, &w, &h);
    if ((uint64_t)w * h > MAX_PIXELS) return say("the image is larger than this example's buffer") + 5;
    rtk_render_region(scene, 0, 0, w, h, rgb);
    char hash[RTK_HASH_SIZE];
    rtk_render_hash(rgb, w, h, hash);
    return say(hash);
}

/* The entry point: align the stack, run, exit with its status. */
#if defined(__x86_64__)
__asm__(".globl _start\n_start:\n xor %rbp, %rbp\n and $-16, %rsp\n call blob_hash_main\n mov %eax, %edi\n"
        " mov $60, %eax\n syscall\n");
#else
__asm__(".globl _start\n_start:\n mov x29, #0\n mov x30, #0\n bl blob_hash_main\n mov x8, #93\n svc 0\n");
#endif
