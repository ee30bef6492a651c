//! The boundary: errors as codes and a thread-local message, panics caught, pointers and
//! lengths checked before they become references.

use super::{
    GSPH_ERR_ARGUMENT, GSPH_ERR_BUSY, GSPH_ERR_INTERNAL, GSPH_ERR_IO, GSPH_ERR_POINTER,
    GSPH_ERR_SCENE, GSPH_ERR_SIMULATION, GSPH_OK,
};
use gsph_rs::api::ApiError;
use std::cell::RefCell;
use std::ffi::{c_char, c_int, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// A failed call: its code and one-line message.
pub struct Failure {
    code: c_int,
    msg: String,
}

impl Failure {
    pub fn pointer(msg: impl Into<String>) -> Self {
        Failure {
            code: GSPH_ERR_POINTER,
            msg: msg.into(),
        }
    }
    pub fn argument(msg: impl Into<String>) -> Self {
        Failure {
            code: GSPH_ERR_ARGUMENT,
            msg: msg.into(),
        }
    }
    pub fn scene(msg: impl Into<String>) -> Self {
        Failure {
            code: GSPH_ERR_SCENE,
            msg: msg.into(),
        }
    }
    pub fn busy(msg: impl Into<String>) -> Self {
        Failure {
            code: GSPH_ERR_BUSY,
            msg: msg.into(),
        }
    }
    pub fn internal(msg: impl Into<String>) -> Self {
        Failure {
            code: GSPH_ERR_INTERNAL,
            msg: msg.into(),
        }
    }
}

impl From<ApiError> for Failure {
    fn from(e: ApiError) -> Self {
        let code = match &e {
            ApiError::Scene(_) => GSPH_ERR_SCENE,
            ApiError::Simulation(_) => GSPH_ERR_SIMULATION,
            ApiError::Argument(_) => GSPH_ERR_ARGUMENT,
            ApiError::Io(_) => GSPH_ERR_IO,
            // only the C ABI stops a call: its handle was destroyed during it
            ApiError::Stopped(_) => GSPH_ERR_BUSY,
        };
        Failure {
            code,
            msg: e.to_string(),
        }
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_error(msg: &str) {
    // one line, and no interior NUL
    let line: String = msg
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('\0', " ");
    // try_with: a call during thread teardown keeps no message rather than aborting
    let _ = LAST_ERROR.try_with(|e| *e.borrow_mut() = CString::new(line).unwrap_or_default());
}

/// The message of the last failed call on this thread ("" after a success), valid until
/// the next gsph call on this thread. Never null.
///
/// Thread safety: any thread; each thread has its own message.
#[no_mangle]
pub extern "C" fn gsph_last_error() -> *const c_char {
    LAST_ERROR
        .try_with(|e| e.borrow().as_ptr())
        .unwrap_or(c"".as_ptr())
}

/// Runs `f`, turning its error or panic into a status and the thread's message.
pub fn guard(f: impl FnOnce() -> Result<(), Failure>) -> c_int {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => {
            set_error("");
            GSPH_OK
        }
        Ok(Err(e)) => {
            set_error(&e.msg);
            e.code
        }
        Err(p) => {
            let what = p
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| p.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown".into());
            set_error(&format!(
                "internal error (a bug in gsph, please report it): {what}"
            ));
            GSPH_ERR_INTERNAL
        }
    }
}

fn check<T>(p: *const T, len: usize, name: &str) -> Result<(), Failure> {
    if p.is_null() {
        return Err(Failure::pointer(format!("{name}: null pointer")));
    }
    if !p.is_aligned() {
        return Err(Failure::pointer(format!(
            "{name}: misaligned pointer (needs {}-byte alignment)",
            std::mem::align_of::<T>()
        )));
    }
    if len
        .checked_mul(std::mem::size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(Failure::pointer(format!(
            "{name}: length {len} is too large"
        )));
    }
    Ok(())
}

/// `len` values at `p` (null allowed when `len` is 0).
pub unsafe fn slice<'a, T>(p: *const T, len: usize, name: &str) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    check(p, len, name)?;
    // SAFETY: non-null, aligned, size within isize::MAX; the caller promises `len` values.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// `len` writable values at `p` (null allowed when `len` is 0).
pub unsafe fn slice_mut<'a, T>(p: *mut T, len: usize, name: &str) -> Result<&'a mut [T], Failure> {
    if len == 0 {
        return Ok(&mut []);
    }
    check(p.cast_const(), len, name)?;
    // SAFETY: as `slice`, and the caller promises the buffer is writable and unaliased.
    Ok(unsafe { std::slice::from_raw_parts_mut(p, len) })
}

/// The output slot at `p`.
pub unsafe fn out<'a, T>(p: *mut T, name: &str) -> Result<&'a mut T, Failure> {
    check(p.cast_const(), 1, name)?;
    // SAFETY: non-null and aligned; the caller promises a writable T.
    Ok(unsafe { &mut *p })
}

/// Writes `v` to the optional output `p` (nothing when `p` is null).
pub unsafe fn put<T>(p: *mut T, name: &str, v: T) -> Result<(), Failure> {
    if !p.is_null() {
        *unsafe { out(p, name)? } = v;
    }
    Ok(())
}

/// The struct at `p`.
pub unsafe fn get<'a, T>(p: *const T, name: &str) -> Result<&'a T, Failure> {
    check(p, 1, name)?;
    // SAFETY: non-null and aligned; the caller promises a valid T.
    Ok(unsafe { &*p })
}

/// The NUL-terminated UTF-8 string at `p`.
pub unsafe fn cstr<'a>(p: *const c_char, name: &str) -> Result<&'a str, Failure> {
    if p.is_null() {
        return Err(Failure::pointer(format!("{name}: null string")));
    }
    // SAFETY: non-null; the caller promises a NUL-terminated string.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|e| Failure::argument(format!("{name}: not UTF-8 ({e})")))
}

/// `n` strings at `p` (null allowed when `n` is 0).
pub unsafe fn strings(
    p: *const *const c_char,
    n: usize,
    name: &str,
) -> Result<Vec<String>, Failure> {
    let ptrs = unsafe { slice(p, n, name)? };
    ptrs.iter()
        .enumerate()
        .map(|(k, &s)| unsafe { cstr(s, &format!("{name}[{k}]")) }.map(str::to_string))
        .collect()
}

/// Copies `text` with a NUL into `buf` of `len` bytes, its length with the NUL into the
/// optional `needed`; a `buf` too small gets nothing and fails with GSPH_ERR_ARGUMENT
/// (`what` names the text).
pub unsafe fn text_out(
    text: &str,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
    what: &str,
) -> Result<(), Failure> {
    let need = text.len() + 1;
    unsafe { put(needed, "needed", need)? };
    if len < need {
        return Err(Failure::argument(format!(
            "buf: {len} bytes, the {what} needs {need}"
        )));
    }
    let b = unsafe { slice_mut(buf.cast::<u8>(), len, "buf")? };
    b[..text.len()].copy_from_slice(text.as_bytes());
    b[text.len()] = 0;
    Ok(())
}
