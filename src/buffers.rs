//! Large output buffers of the refinement kernels, backed by huge pages where the system allows.
//!
//! A refined level is hundreds of megabytes written exactly once. On Linux the first write to
//! each 4 KiB page of a fresh allocation costs a page fault, and for the refinement kernels
//! those faults take about as long as computing the points in the page (measured on a 6.4M-point
//! Catmull-Clark level: 90-110 ms to fault 154 MB in, 20-30 ms with 2 MiB pages). So the kernels
//! allocate their outputs zeroed (fresh, untouched pages) and ask the kernel to back them with
//! transparent huge pages (`madvise(MADV_HUGEPAGE)`, honoured when the THP mode is `always` or
//! `madvise`). It is only a hint: it changes no value, and on other systems, with THP disabled,
//! or for buffers below [`MIN_BYTES`] nothing happens.

/// Buffers smaller than this are left alone (a few huge pages at most).
const MIN_BYTES: usize = 8 << 20;

/// Asks for huge pages behind the untouched buffer `v` (call it before the first write).
pub(crate) fn advise_huge<T>(v: &mut [T]) {
    let bytes = std::mem::size_of_val(v);
    if bytes < MIN_BYTES {
        return;
    }
    #[cfg(target_os = "linux")]
    {
        const PAGE: usize = 4096;
        let start = v.as_mut_ptr() as usize;
        let (a, b) = (
            (start + PAGE - 1) & !(PAGE - 1),
            (start + bytes) & !(PAGE - 1),
        );
        // SAFETY: `[a, b)` lies inside the buffer `v` owns; MADV_HUGEPAGE only changes how the
        // kernel backs those pages, never their contents. The result is ignored: a refusal
        // (THP not compiled in) leaves ordinary pages.
        unsafe {
            libc::madvise(a as *mut libc::c_void, b - a, libc::MADV_HUGEPAGE);
        }
    }
}

/// A zeroed vector of `n` elements (`zero` must be the all-zero bit pattern, such as `0u32` or
/// `[0.0; 3]`, so the allocation comes straight from fresh pages), advised for huge pages.
pub(crate) fn zeroed<T: Clone>(n: usize, zero: T) -> Vec<T> {
    let mut v = vec![zero; n];
    advise_huge(&mut v);
    v
}
