//! Bare-metal runtime of the firmware runner (`core/examples/firmware_flyer.rs`) on QEMU's
//! `mps2-an386` board (Cortex-M4F), hand-written so the core gains no dependency: the
//! vector table and reset handler (FPU enabled, `.data` copied from flash, `.bss` zeroed,
//! the stack painted so its high-water mark can be measured), ARM semihosting (console,
//! host clock, exit status) and the panic and fault handlers. The memory layout is
//! `core/firmware/mps2_an386.ld`; `scripts/firmware.sh` builds and runs it.

use core::arch::{asm, global_asm};
use core::fmt;
use core::ptr::{addr_of, read_volatile};

/// The word the reset handler writes over the whole stack before `main` runs.
const PAINT: u32 = 0x5AC4_C0DE;

// The vector table (initial stack pointer, reset and the system exceptions; no device
// interrupt is ever enabled) and the reset handler. The reset handler uses no stack and
// runs before any Rust code: Rust code compiled for `eabihf` uses the FPU registers, so
// CP10/CP11 must be enabled first, and statics must hold their initial values.
global_asm!(
    ".section .vector_table, \"a\", %progbits",
    ".global gsph_vectors",
    "gsph_vectors:",
    ".word __estack",
    ".word gsph_reset",
    ".word gsph_fault_entry", // NMI
    ".word gsph_fault_entry", // HardFault
    ".word gsph_fault_entry", // MemManage
    ".word gsph_fault_entry", // BusFault
    ".word gsph_fault_entry", // UsageFault
    ".word 0, 0, 0, 0",
    ".word gsph_fault_entry", // SVCall
    ".word gsph_fault_entry", // DebugMonitor
    ".word 0",
    ".word gsph_fault_entry", // PendSV
    ".word gsph_fault_entry", // SysTick
    "",
    ".section .text.gsph_reset, \"ax\", %progbits",
    ".global gsph_reset",
    ".type gsph_reset, %function",
    ".thumb_func",
    "gsph_reset:",
    // CPACR |= full access to CP10 and CP11 (the FPU)
    "ldr r0, =0xE000ED88",
    "ldr r1, [r0]",
    "orr r1, r1, #0x00F00000",
    "str r1, [r0]",
    "dsb",
    "isb",
    // .data: copy the initial values from their load address in flash
    "ldr r0, =__sdata",
    "ldr r1, =__edata",
    "ldr r2, =__sidata",
    "1: cmp r0, r1",
    "bhs 2f",
    "ldr r3, [r2], #4",
    "str r3, [r0], #4",
    "b 1b",
    // .bss: zero
    "2: ldr r0, =__sbss",
    "ldr r1, =__ebss",
    "movs r3, #0",
    "3: cmp r0, r1",
    "bhs 4f",
    "str r3, [r0], #4",
    "b 3b",
    // the stack, from its bottom to the stack pointer: paint
    "4: ldr r0, =__sstack",
    "mov r1, sp",
    "ldr r3, ={paint}",
    "5: cmp r0, r1",
    "bhs 6f",
    "str r3, [r0], #4",
    "b 5b",
    "6: bl gsph_main",
    "b 6b",
    ".ltorg",
    "",
    ".section .text.gsph_fault_entry, \"ax\", %progbits",
    ".global gsph_fault_entry",
    ".type gsph_fault_entry, %function",
    ".thumb_func",
    "gsph_fault_entry:",
    "mrs r0, ipsr",
    "b gsph_fault",
    paint = const PAINT,
);

extern "C" {
    static __sstack: u32;
    static __estack: u32;
}

/// Any exception (a fault: nothing else is enabled) ends the run with a failure.
#[no_mangle]
extern "C" fn gsph_fault(ipsr: u32) -> ! {
    let mut out = Console::new();
    let _ = fmt::Write::write_fmt(
        &mut out,
        format_args!("error: exception {} (a fault)\n", ipsr & 0x1ff),
    );
    exit(false)
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    let mut out = Console::new();
    let _ = fmt::Write::write_fmt(&mut out, format_args!("error: panic: {info}\n"));
    exit(false)
}

const SYS_WRITE0: u32 = 0x04;
const SYS_EXIT: u32 = 0x18;
const SYS_ELAPSED: u32 = 0x30;
const SYS_TICKFREQ: u32 = 0x31;
/// `SYS_EXIT` reasons: QEMU exits with status 0 for the first, 1 for any other.
const ADP_STOPPED_APPLICATION_EXIT: usize = 0x20026;
const ADP_STOPPED_RUNTIME_ERROR_UNKNOWN: usize = 0x20023;

/// One semihosting call: operation in r0, argument (a value or a pointer to a parameter
/// block) in r1, result in r0; `bkpt 0xab` is the M-profile trap.
///
/// # Safety
/// `arg` must be what the operation expects (a valid pointer where it takes one).
unsafe fn semihost(op: u32, arg: usize) -> isize {
    let r: isize;
    // SAFETY: the debugger (QEMU) services the breakpoint; the caller vouches for `arg`.
    unsafe {
        asm!("bkpt #0xab", inout("r0") op as isize => r, in("r1") arg, options(nostack));
    }
    r
}

/// Ends the run: QEMU exits with status 0 if `ok`, else 1.
pub fn exit(ok: bool) -> ! {
    let reason = if ok {
        ADP_STOPPED_APPLICATION_EXIT
    } else {
        ADP_STOPPED_RUNTIME_ERROR_UNKNOWN
    };
    loop {
        // SAFETY: SYS_EXIT takes the reason code by value on 32-bit targets.
        unsafe { semihost(SYS_EXIT, reason) };
    }
}

/// Nanoseconds of host time since QEMU started (`SYS_ELAPSED` / `SYS_TICKFREQ`), or
/// `None` where the debugger does not implement them.
pub fn host_ns() -> Option<u64> {
    let mut ticks = [0u32; 2];
    // SAFETY: SYS_ELAPSED writes two words (low, high) at the pointer.
    if unsafe { semihost(SYS_ELAPSED, ticks.as_mut_ptr() as usize) } != 0 {
        return None;
    }
    // SAFETY: SYS_TICKFREQ takes no argument.
    let freq = unsafe { semihost(SYS_TICKFREQ, 0) };
    if freq <= 0 {
        return None;
    }
    let ticks = (ticks[1] as u64) << 32 | ticks[0] as u64;
    Some((ticks as u128 * 1_000_000_000 / freq as u128) as u64)
}

/// Bytes of the stack the run has used (its high-water mark: the painted words no longer
/// intact) and bytes reserved.
pub fn stack_use() -> (usize, usize) {
    let bottom = addr_of!(__sstack);
    let top = addr_of!(__estack);
    let mut p = bottom;
    // SAFETY: [bottom, top) is the stack region of the linker script, word aligned.
    while p < top && unsafe { read_volatile(p) } == PAINT {
        p = p.wrapping_add(1);
    }
    (top as usize - p as usize, top as usize - bottom as usize)
}

/// The semihosting console (`SYS_WRITE0`), one line at a time through a small buffer.
pub struct Console {
    buf: [u8; 128],
    len: usize,
}

impl Console {
    /// An empty console buffer.
    pub const fn new() -> Self {
        Console {
            buf: [0; 128],
            len: 0,
        }
    }

    fn flush(&mut self) {
        if self.len > 0 {
            self.buf[self.len] = 0;
            // SAFETY: the buffer is NUL-terminated and outlives the call.
            unsafe { semihost(SYS_WRITE0, self.buf.as_ptr() as usize) };
            self.len = 0;
        }
    }
}

impl fmt::Write for Console {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for &b in s.as_bytes() {
            self.buf[self.len] = b;
            self.len += 1;
            if b == b'\n' || self.len == self.buf.len() - 1 {
                self.flush();
            }
        }
        Ok(())
    }
}

impl Drop for Console {
    fn drop(&mut self) {
        self.flush();
    }
}
