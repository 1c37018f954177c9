/* Check an encoded LCM payload against a type before decoding it.
 *
 * lcm-gen's C decoders allocate as they go and return early on error without
 * freeing (so every bad message would leak), and they accept strings that
 * are not NUL-terminated. This walker reads the wire format with the type's
 * field introspection, allocating nothing, and says whether a decode would
 * consume the payload exactly and safely. */
#ifndef AUV_LCM_VALIDATE_H
#define AUV_LCM_VALIDATE_H

#include "common/auv_types.h"

/* Bytes a well-formed message body of `type` starting at buf occupies
 * (fingerprint excluded), or -1 if the bytes cannot be such a body. */
int lcm_validate_body(const auv_type_entry_t *type, const void *buf, int len);

#endif
