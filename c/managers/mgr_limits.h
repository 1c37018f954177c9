/* Every size limit of chasm-manager, in one place. Each limit a message or a
 * file can exceed has a refusal that says it (docs/managers.md and
 * docs/channels.md, "Commands and their limits", quote these numbers). */
#ifndef MGR_LIMITS_H
#define MGR_LIMITS_H

/* LCM's channel name limit, characters. Every channel the manager names must
 * fit: <VEHICLE>.CHASM.<NAME> and <VEHICLE>.PLUGIN_UPLOAD are the longest. */
#define MGR_MAX_CHANNEL 63
#define MGR_MAX_VEHICLE 48                  /* --vehicle: <VEHICLE>.PLUGIN_UPLOAD fits */

/* Command line. */
#define MGR_MAX_PARAMS 64                   /* -D overrides */
#define MGR_MAX_RATE_HZ 1000                /* --rate */
#define MGR_ON_CHANGE_PERIOD_US 1000000     /* an `on_change` output unchanged goes out once per this */
#define MGR_MAX_PLUGIN_PATH 16              /* --plugin-path folders (with --plugin-dir) */
#define MGR_MAX_FUTURE_TOLERANCE_S 3600     /* --future-tolerance */
#define MGR_MAX_CLOCK_JUMP_S 86400          /* --max-clock-jump */

/* Files. */
#define MGR_MAX_BIND_BYTES (1024 * 1024)    /* a binding file (each included file too) */
#define MGR_MAX_BIND_INCLUDE_DEPTH 8        /* files open at once through `include` */

/* Mission commands and their acks. */
#define MGR_MAX_PLAN_BYTES (256 * 1024)     /* LOAD_PLAN plan_text, the documented maximum */
#define MGR_MIN_PLAN_BYTES (32 * 1024)      /* the least a too-small receive buffer lowers it to */
#define MGR_MAX_PLAN_NAME 255               /* LOAD_PLAN plan_name, characters */
#define MGR_MAX_REASON 1024                 /* a command's reason, characters */
#define MGR_ACK_MAX_ERRORS 5                /* errors quoted in a rejected LOAD_PLAN's ack */
#define MGR_ACK_MAX_CHARS 2000              /* an ack's message, characters */
#define MGR_ACK_FIELD_CHARS 40              /* a bad field quoted in an ack, characters */

/* The plan's structure (<VEHICLE>.PLAN.<NAME>, mgr_structure.h): sent again
 * this often in mission time, for a view or recorder that started late; one
 * that would encode to more than MGR_MAX_STRUCTURE_BYTES goes out with its
 * tables empty and `truncated` set (a view says why it cannot draw it). */
#define MGR_STRUCTURE_PERIOD_US 10000000
#define MGR_MAX_STRUCTURE_BYTES (1024 * 1024)
#define MGR_STATUS_MAX_LIVE_TESTS 128       /* chasm_status_t.live_test_value */
#define MGR_STATUS_MAX_VAR_VALUES 128       /* chasm_status_t.var_value */

/* Plugin uploads: the Loader's own limit (CM_PLUGIN_MAX_BYTES in
 * c/chasm/cm_elf_check.h), since a bigger upload could never load. */
#define MGR_MAX_UPLOAD_BYTES (64 * 1024 * 1024)

/* The LCM receive buffer. LCM fragments a large message into datagrams of up
 * to 64 KiB; liblcm's reader thread drains the socket as fragments come, but a
 * loaded machine can starve it, so the buffer must hold a whole message of
 * the maximum size plus two fragments of slack for the kernel's per-datagram
 * overhead and other traffic. (Measured on loopback: with 425984 bytes
 * granted, a 400 KB message arrives and a 1 MB one does not.) */
#define MGR_LCM_FRAGMENT_BYTES (64 * 1024)
/* What the manager asks for: more than the maximum needs, because a plan over
 * the maximum must still arrive whole to be refused with its size (an
 * over-size plan the buffer cannot hold is lost without an answer; a 400 KB
 * plan into a 393 KB buffer was, on a loaded machine and under ASan). */
#define MGR_RECV_BUFFER_BYTES (2 * 1024 * 1024)

#endif
