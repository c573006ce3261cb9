//! Empty: the check is `tests/synctest.rs`.
