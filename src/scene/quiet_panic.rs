//! Catching a panic of a file reader (glTF, OBJ) without its message or backtrace reaching stderr:
//! the caller reports one clean error instead.
//!
//! The panic hook is process-wide, so it is replaced once by one that stays silent only on a thread
//! inside `catch` and hands every other panic to the hook it replaced.

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

static INSTALL: Once = Once::new();

/// Runs `f`; a panic inside it prints nothing and gives None.
pub(crate) fn catch<T>(f: impl FnOnce() -> T) -> Option<T> {
    INSTALL.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let out = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    out.ok()
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_panic_inside_gives_none_and_a_value_passes_through() {
        assert_eq!(super::catch(|| 7), Some(7));
        let r: Option<()> = super::catch(|| panic!("inside the reader"));
        assert!(r.is_none());
        // Still quiet-free afterwards: the flag was restored.
        assert!(!super::QUIET.with(std::cell::Cell::get));
    }
}
