/* The few POSIX calls davit_io_files needs that Fortran cannot make portably: stat()'s
 * struct layout differs between platforms and C libraries, open() is variadic and its
 * flags are macros, and errno is a macro. Each function is a thin wrapper that returns
 * plain integers (an errno value on failure) so that the Fortran side owns every
 * decision and every message. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

/* Kinds returned by davit_file_kind; davit_io_files names them. */
enum { KIND_NONE = 0, KIND_REGULAR, KIND_FOLDER, KIND_PIPE, KIND_CHAR_DEVICE,
       KIND_BLOCK_DEVICE, KIND_SOCKET, KIND_OTHER };

/* What `path` is, following symbolic links (/dev/stdin, /dev/fd/N); KIND_NONE with
 * *err = errno when stat fails (ENOENT: absent). */
int davit_file_kind(const char *path, int *err) {
  struct stat st;
  *err = 0;
  if (stat(path, &st) != 0) {
    *err = errno;
    return KIND_NONE;
  }
  if (S_ISREG(st.st_mode)) return KIND_REGULAR;
  if (S_ISDIR(st.st_mode)) return KIND_FOLDER;
  if (S_ISFIFO(st.st_mode)) return KIND_PIPE;
  if (S_ISCHR(st.st_mode)) return KIND_CHAR_DEVICE;
  if (S_ISBLK(st.st_mode)) return KIND_BLOCK_DEVICE;
  if (S_ISSOCK(st.st_mode)) return KIND_SOCKET;
  return KIND_OTHER;
}

/* 1 when both paths exist and name one file (same device and inode), else 0. */
int davit_same_file(const char *a, const char *b) {
  struct stat sa, sb;
  if (stat(a, &sa) != 0 || stat(b, &sb) != 0) return 0;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* A descriptor for reading `path` to its end. O_NONBLOCK keeps the open itself from
 * waiting for a writer (a FIFO nobody writes to); it is cleared afterwards so that reads
 * from a pipe wait for its data. -1 with *err = errno on failure. */
int davit_open_read(const char *path, int *err) {
  int fd, flags;
  *err = 0;
  fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    *err = errno;
    return -1;
  }
  flags = fcntl(fd, F_GETFL);
  if (flags == -1 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) == -1) {
    *err = errno;
    close(fd);
    return -1;
  }
  return fd;
}

/* Up to n bytes into buf, retried when a signal interrupts; 0 at the end of the file,
 * -1 with *err = errno on failure. */
long davit_read(int fd, char *buf, long n, int *err) {
  ssize_t got;
  *err = 0;
  do {
    got = read(fd, buf, (size_t)n);
  } while (got < 0 && errno == EINTR);
  if (got < 0) *err = errno;
  return (long)got;
}

int davit_close(int fd) { return close(fd); }

/* `path` created exclusively and the n bytes of `text` written and flushed to the disk:
 * 0, or an errno value (ENOSPC for a short write); *opened says whether the file was
 * created (it is then left in place whatever the outcome). */
static int write_exclusive(const char *path, const char *text, long n, int *opened) {
  int fd, status = 0;
  ssize_t put;
  fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
  *opened = fd >= 0;
  if (fd < 0) return errno;
  put = write(fd, text, (size_t)n);
  if (put < 0) status = errno;
  else if (put != n) status = ENOSPC;
  if (fsync(fd) != 0 && status == 0) status = errno;
  if (close(fd) != 0 && status == 0) status = errno;
  return status;
}

/* `path` created exclusively and written in place (where hard links are not supported):
 * on a failed write it is removed again. 0, or an errno value. */
static int create_in_place(const char *path, const char *text, long n) {
  int opened, status = write_exclusive(path, text, n, &opened);
  if (status != 0 && opened) unlink(path);
  return status;
}

/* `path` holding the n bytes of `text`, whole or not at all: the text goes into the
 * private file `tmp` first (flushed to the disk), which then becomes `path`, by link()
 * when `replace` is 0 (which never replaces: -1 when `path` exists) or by rename()
 * otherwise (atomic). A full disk leaves no empty or half-written file under `path`.
 * 0, -1 (exists) or an errno value; `tmp` never remains. */
int davit_write_whole(const char *path, const char *tmp, const char *text, long n,
                      int replace) {
  int opened, status;
  unlink(tmp);  /* named after this process: a leftover is a dead namesake's */
  status = write_exclusive(tmp, text, n, &opened);
  if (!opened) return status;
  if (status == 0 && replace) {
    if (rename(tmp, path) != 0) status = errno;
  } else if (status == 0 && link(tmp, path) != 0) {
    status = errno == EEXIST ? -1 : errno;
  }
  unlink(tmp);
  if (!replace && (status == EPERM || status == EOPNOTSUPP || status == ENOSYS)) {
    status = create_in_place(path, text, n);  /* no hard links (FAT, some FUSE) */
    if (status == EEXIST) status = -1;
  }
  return status;
}

/* A new empty file `path` (exclusive): 0, or the errno value that says why not. */
int davit_create_empty(const char *path) {
  int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) return errno;
  return close(fd) != 0 ? errno : 0;
}

/* The longest file name the file system of folder `dir` allows (NAME_MAX), -1 if unknown. */
long davit_name_max(const char *dir) { return pathconf(dir, _PC_NAME_MAX); }

/* The text of errno value `err` into buf (n bytes, blank-padded for Fortran). */
void davit_errno_text(int err, char *buf, int n) {
  const char *text = strerror(err);
  int k = 0;
  for (; k < n && text[k] != '\0'; ++k) buf[k] = text[k];
  for (; k < n; ++k) buf[k] = ' ';
}
