//! [`Recycling`], the `tetray` CLI's global allocator.
//!
//! Loading a mesh is a sequence of large arrays, each built from the one
//! before and then dropped: the file's bytes, the decoded connectivity, the
//! tetrahedra, the face table, the renumbered copies, the walk records. With
//! the system allocator every one of them is a fresh `mmap`, so every page is
//! faulted in and zeroed by the kernel again, although the process has just
//! given back as much. On a 10 M-tetrahedron load that is 3.5 GB of page
//! faults for a peak of under 1 GB, and on a virtual machine a fault costs
//! microseconds.
//!
//! [`Recycling`] keeps large freed blocks (at least [`LARGE`] bytes) mapped
//! and hands them to the next large allocation: the smallest kept block that
//! is big enough (its surplus kept apart); or, when none is,
//! a fresh mapping into which `mremap` moves the kept blocks' pages, largest
//! first, until it is covered (only the rest is faulted in anew). Small
//! allocations go to the system allocator unchanged.
//!
//! Kept blocks stay resident until the next large allocation takes them,
//! until [`Recycling::release`], or until a larger freed block evicts them
//! (at most [`SLOTS`] are kept). A program calls `release` once its large
//! temporaries are gone.
//!
//! Outside Linux (no `mremap`) every allocation goes to the system
//! allocator.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::{Mutex, MutexGuard};

/// Allocations of at least this many bytes are mapped and recycled here.
/// At 16 MiB the 1 M-tetrahedron shell's load peaked at 163 MB instead of
/// 104 MB: kept blocks idled while the arrays just below the bound grew
/// glibc's heap. At 1 MiB it peaks at 106 MB, and the 10 M load at 944 MB
/// (951 MB with the system allocator alone).
pub const LARGE: usize = 1 << 20;

/// How many freed blocks are kept at most.
pub const SLOTS: usize = 8;

/// A mapped block: address and length in bytes (a multiple of the page).
#[derive(Clone, Copy)]
struct Block {
    addr: usize,
    len: usize,
}

struct Cache {
    blocks: [Block; SLOTS],
    count: usize,
}

/// A global allocator that recycles large blocks (see the crate docs).
pub struct Recycling {
    cache: Mutex<Cache>,
}

impl Default for Recycling {
    fn default() -> Self {
        Self::new()
    }
}

impl Recycling {
    pub const fn new() -> Self {
        Recycling {
            cache: Mutex::new(Cache {
                blocks: [Block { addr: 0, len: 0 }; SLOTS],
                count: 0,
            }),
        }
    }

    /// Returns every kept block to the system.
    pub fn release(&self) {
        let mut cache = self.lock();
        while cache.count > 0 {
            cache.count -= 1;
            let block = cache.blocks[cache.count];
            unmap(block);
        }
    }

    /// Bytes kept mapped for reuse.
    pub fn kept_bytes(&self) -> usize {
        let cache = self.lock();
        cache.blocks[..cache.count].iter().map(|b| b.len).sum()
    }

    fn lock(&self) -> MutexGuard<'_, Cache> {
        // Nothing panics while the lock is held; a poisoned lock still holds
        // a consistent list.
        self.cache.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Takes the smallest kept block at least `len` bytes long.
    fn take_fit(&self, len: usize) -> Option<Block> {
        let mut cache = self.lock();
        let kept = &cache.blocks[..cache.count];
        let i = (0..kept.len())
            .filter(|&i| kept[i].len >= len)
            .min_by_key(|&i| kept[i].len)?;
        Some(cache.remove(i))
    }

    /// Takes the largest kept block.
    fn take_largest(&self) -> Option<Block> {
        let mut cache = self.lock();
        let kept = &cache.blocks[..cache.count];
        let i = (0..kept.len()).max_by_key(|&i| kept[i].len)?;
        Some(cache.remove(i))
    }

    /// Keeps a freed block, evicting the smallest kept one if it is full
    /// (or returning this one, if it is the smallest).
    fn keep(&self, block: Block) {
        let mut cache = self.lock();
        if cache.count < SLOTS {
            let n = cache.count;
            cache.blocks[n] = block;
            cache.count += 1;
            return;
        }
        let smallest = (0..SLOTS).min_by_key(|&i| cache.blocks[i].len).unwrap_or(0);
        let out = if cache.blocks[smallest].len < block.len {
            std::mem::replace(&mut cache.blocks[smallest], block)
        } else {
            block
        };
        drop(cache);
        unmap(out);
    }

    /// Keeps what follows the first `used` bytes of `block`, if anything.
    fn keep_rest(&self, block: Block, used: usize) {
        if block.len > used {
            self.keep(Block {
                addr: block.addr + used,
                len: block.len - used,
            });
        }
    }

    /// Maps `size` bytes (`size >= LARGE`): the smallest kept block that
    /// is long enough (the rest of it kept apart), or else a fresh mapping
    /// into which the kept blocks are moved, largest first, until it is
    /// covered (so no kept page stays idle while a large allocation faults
    /// in new ones).
    fn alloc_large(&self, size: usize, zero: bool) -> *mut u8 {
        let len = page_round(size);
        if let Some(block) = self.take_fit(len) {
            self.keep_rest(block, len);
            let ptr = block.addr as *mut u8;
            if zero {
                // SAFETY: `block` is a mapping of at least `len >= size`
                // writable bytes owned by no one else.
                unsafe { ptr.write_bytes(0, size) };
            }
            return ptr;
        }
        let ptr = map(len);
        if ptr.is_null() {
            return ptr;
        }
        let mut filled = 0;
        while filled < len {
            let Some(block) = self.take_largest() else {
                break;
            };
            let n = block.len.min(len - filled);
            let to = ptr as usize + filled;
            // SAFETY: `block` is a mapping of ours that no one uses, and
            // `to .. to + n` lies inside the fresh mapping `ptr`.
            if !unsafe { move_pages(block.addr, n, to) } {
                unmap(block);
                break;
            }
            self.keep_rest(block, n);
            if zero {
                // SAFETY: `to .. to + n` is now the moved pages, inside
                // the new allocation.
                unsafe { (to as *mut u8).write_bytes(0, n) };
            }
            filled += n;
        }
        ptr
    }
}

impl Cache {
    /// Removes and returns block `i`.
    fn remove(&mut self, i: usize) -> Block {
        let block = self.blocks[i];
        self.count -= 1;
        self.blocks[i] = self.blocks[self.count];
        block
    }
}

/// Whether the block of `layout` is mapped here rather than by `System`.
fn is_large(layout: Layout) -> bool {
    cfg!(target_os = "linux") && layout.size() >= LARGE && layout.align() <= page_size()
}

fn page_size() -> usize {
    // SAFETY: sysconf has no preconditions.
    let page = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    usize::try_from(page).unwrap_or(4096)
}

fn page_round(size: usize) -> usize {
    let page = page_size();
    size.div_ceil(page) * page
}

/// A fresh anonymous mapping of `len` bytes, or null.
fn map(len: usize) -> *mut u8 {
    // SAFETY: an anonymous private mapping at an address of the kernel's
    // choosing touches no existing memory.
    let ptr = unsafe {
        libc::mmap(
            std::ptr::null_mut(),
            len,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        )
    };
    if ptr == libc::MAP_FAILED {
        std::ptr::null_mut()
    } else {
        ptr.cast()
    }
}

fn unmap(block: Block) {
    // SAFETY: `block` is (a page-aligned tail of) a mapping of ours that no
    // one uses any more. munmap cannot fail on such a range.
    unsafe { libc::munmap(block.addr as *mut libc::c_void, block.len) };
}

/// Resizes the mapping `block` to `len` bytes, moving it if needed; null
/// (the mapping unchanged) on failure, as when `block` spans several
/// mappings.
///
/// # Safety
/// `block` must be a whole block of this allocator.
#[cfg(target_os = "linux")]
unsafe fn remap(block: Block, len: usize) -> *mut u8 {
    // SAFETY: the caller's contract; MREMAP_MAYMOVE keeps the contents.
    let ptr = unsafe {
        libc::mremap(
            block.addr as *mut libc::c_void,
            block.len,
            len,
            libc::MREMAP_MAYMOVE,
        )
    };
    if ptr == libc::MAP_FAILED {
        std::ptr::null_mut()
    } else {
        ptr.cast()
    }
}

/// Moves the pages of `from .. from + len` to `to .. to + len` (replacing
/// what was mapped there); whether it did.
///
/// # Safety
/// `from .. from + len` must be (the start of) a mapping of ours that no
/// one uses, and `to .. to + len` a page-aligned range of a mapping of ours
/// that no one uses.
#[cfg(target_os = "linux")]
unsafe fn move_pages(from: usize, len: usize, to: usize) -> bool {
    // SAFETY: the caller's contract: both ranges are ours and unused.
    let ptr = unsafe {
        libc::mremap(
            from as *mut libc::c_void,
            len,
            len,
            libc::MREMAP_MAYMOVE | libc::MREMAP_FIXED,
            to as *mut libc::c_void,
        )
    };
    ptr != libc::MAP_FAILED
}

#[cfg(not(target_os = "linux"))]
unsafe fn remap(_block: Block, _len: usize) -> *mut u8 {
    std::ptr::null_mut()
}

#[cfg(not(target_os = "linux"))]
unsafe fn move_pages(_from: usize, _len: usize, _to: usize) -> bool {
    false
}

// SAFETY: large blocks are page-aligned mappings of at least the layout's
// size (and `is_large` admits no alignment above a page); each is owned by
// one allocation until it is freed and only then kept for reuse. Everything
// else is `System`'s.
unsafe impl GlobalAlloc for Recycling {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if is_large(layout) {
            self.alloc_large(layout.size(), false)
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { System.alloc(layout) }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if is_large(layout) {
            self.alloc_large(layout.size(), true)
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { System.alloc_zeroed(layout) }
        }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if is_large(layout) {
            self.keep(Block {
                addr: ptr as usize,
                len: page_round(layout.size()),
            });
        } else {
            // SAFETY: the caller's contract, passed on.
            unsafe { System.dealloc(ptr, layout) }
        }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller guarantees `new_size`, rounded up to the
        // alignment, does not overflow isize.
        let new_layout = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
        match (is_large(layout), is_large(new_layout)) {
            // SAFETY: the caller's contract, passed on.
            (false, false) => unsafe { System.realloc(ptr, layout, new_size) },
            (true, true) => {
                let block = Block {
                    addr: ptr as usize,
                    len: page_round(layout.size()),
                };
                let len = page_round(new_size);
                if len == block.len {
                    return ptr;
                }
                // SAFETY: `ptr` is a whole block of ours (a large one).
                let moved = unsafe { remap(block, len) };
                if !moved.is_null() {
                    return moved;
                }
                // A block made of moved pages may span mappings that the
                // kernel did not merge, which mremap refuses: copy instead.
                // SAFETY: the caller's contract, as below.
                unsafe { self.realloc_by_copy(ptr, layout, new_layout) }
            }
            // SAFETY: the caller's contract.
            _ => unsafe { self.realloc_by_copy(ptr, layout, new_layout) },
        }
    }
}

impl Recycling {
    /// Reallocates by allocating, copying and freeing.
    ///
    /// # Safety
    /// As [`GlobalAlloc::realloc`], with `new_layout` the new size and the
    /// old alignment.
    unsafe fn realloc_by_copy(&self, ptr: *mut u8, layout: Layout, new_layout: Layout) -> *mut u8 {
        // SAFETY: `new_layout` has a non-zero size (realloc's contract).
        let new = unsafe { self.alloc(new_layout) };
        if !new.is_null() {
            // SAFETY: both blocks are live, distinct and at least the
            // copied length long.
            unsafe {
                std::ptr::copy_nonoverlapping(ptr, new, layout.size().min(new_layout.size()));
                self.dealloc(ptr, layout);
            }
        }
        new
    }
}

#[cfg(all(test, target_os = "linux"))]
mod tests;
