// Whether AddressSanitizer instruments the file that includes this header: VBR_ADDRESS_SANITIZER
// is then defined (gcc says so by a macro, clang by a feature). The block cache keeps no block
// under it, and the CUDB adapter writes its outputs by plain stores, which it sees.
#ifndef vbr_Sanitizers_h
#define vbr_Sanitizers_h

#if defined(__SANITIZE_ADDRESS__)
#define VBR_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define VBR_ADDRESS_SANITIZER 1
#endif
#endif

#endif
