//! The binding's boundary: every call from Python into an env goes through [`call`] or
//! [`call_mut`], which
//!
//! - refuse a call while another thread is inside the same env (each env is used by one thread at
//!   a time: its calls release the GIL while the physics runs) with a message that says so,
//!   rather than PyO3's bare "Already borrowed";
//! - turn a Rust panic into a `RuntimeError` naming it as an internal error, as a last resort:
//!   PyO3 would raise `pyo3_runtime.PanicException`, a `BaseException` that `except Exception`
//!   in a training loop does not catch. No known input panics (bad input is refused by name); a
//!   panic is a bug, after which the env's state is unknown, so a mutable call that panicked
//!   retires the env and every later call refuses with the same message.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

use pyo3::PyClass;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::pyclass::boolean_struct::False;

/// An env class that can be retired after an internal error.
pub trait Retirable {
    /// Why the env was retired, if it was.
    fn retired(&self) -> Option<&str>;
    /// Retires the env.
    fn retire(&mut self, why: String);
}

/// The error of a call while another thread is inside the env.
fn busy() -> PyErr {
    PyRuntimeError::new_err(
        "this HyQ env is in use by another thread (one of its calls is running): an env is not \
         thread-safe; give each thread its own env, or step many envs with one vector env",
    )
}

/// What a panic said.
fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned())
}

/// The internal error of `what`.
fn internal_error(what: &str, payload: &(dyn Any + Send)) -> String {
    format!(
        "internal error in {what}: {} (a bug in hyq: please report it with the call that caused \
         it; this env cannot be used any more, make a new one)",
        panic_message(payload)
    )
}

/// Runs `body` with the env in `slf` borrowed mutably (see the module docs).
pub fn call_mut<C, T>(
    slf: &Bound<'_, C>,
    what: &str,
    body: impl FnOnce(&mut C) -> PyResult<T>,
) -> PyResult<T>
where
    C: PyClass<Frozen = False> + Retirable,
{
    let mut this = slf.try_borrow_mut().map_err(|_| busy())?;
    if let Some(why) = this.retired() {
        return Err(PyRuntimeError::new_err(why.to_owned()));
    }
    match catch_unwind(AssertUnwindSafe(|| body(&mut this))) {
        Ok(result) => result,
        Err(payload) => {
            let why = internal_error(what, payload.as_ref());
            this.retire(why.clone());
            Err(PyRuntimeError::new_err(why))
        }
    }
}

/// Runs `body` with the env in `slf` borrowed (see the module docs); a read does not change the
/// env, so a panic in it does not retire it.
pub fn call<C, T>(
    slf: &Bound<'_, C>,
    what: &str,
    body: impl FnOnce(&C) -> PyResult<T>,
) -> PyResult<T>
where
    C: PyClass + Retirable,
{
    let this = slf.try_borrow().map_err(|_| busy())?;
    if let Some(why) = this.retired() {
        return Err(PyRuntimeError::new_err(why.to_owned()));
    }
    catch_unwind(AssertUnwindSafe(|| body(&this))).unwrap_or_else(|payload| {
        Err(PyRuntimeError::new_err(internal_error(
            what,
            payload.as_ref(),
        )))
    })
}
