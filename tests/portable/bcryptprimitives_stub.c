/* Test-only stand-in for Windows' bcryptprimitives.dll under wine 8.0, which lacks
 * ProcessPrng (Windows 10 and 11 have it; Rust's std imports it for its random seeds).
 * Built by tests/portable/test_portable.py beside the driver .exe, never put into the FMU:
 *
 *   x86_64-w64-mingw32-gcc -shared -o bcryptprimitives.dll bcryptprimitives_stub.c -ladvapi32 */
#include <windows.h>

/* RtlGenRandom, exported by advapi32 as SystemFunction036. */
BOOLEAN WINAPI SystemFunction036(PVOID buffer, ULONG length);

__declspec(dllexport) BOOL WINAPI ProcessPrng(PBYTE data, SIZE_T size) {
    while (size > 0) {
        ULONG chunk = size > 0x40000000 ? 0x40000000 : (ULONG)size;
        if (!SystemFunction036(data, chunk)) return FALSE;
        data += chunk;
        size -= chunk;
    }
    return TRUE;
}
