//! The words a LS program may not be named.

/// LS's reserved words (docs/reference.md cites the list).
pub(super) const RESERVED: &[&str] = &[
    "ABORT", "AND", "CALL", "CNT", "CONFIG", "ELSE", "END", "ENDFOR", "ENDIF", "FINE", "FOR", "IF",
    "JMP", "LBL", "MOD", "NOT", "OFF", "ON", "OR", "PAUSE", "RUN", "SELECT", "THEN", "TO", "WAIT",
];
