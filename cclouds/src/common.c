#include "cclouds/common.h"

const char *ccl_status_str(ccl_status status)
{
    switch (status) {
    case CCL_OK: return "ok";
    case CCL_EINVAL: return "invalid argument";
    case CCL_ENOMEM: return "out of memory";
    case CCL_EIO: return "input/output error";
    case CCL_ERANGE: return "size or index out of range";
    }
    return "unknown status";
}

int ccl_version(void)
{
    return CCL_VERSION_MAJOR * 10000 + CCL_VERSION_MINOR * 100 + CCL_VERSION_PATCH;
}
