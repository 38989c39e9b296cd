//! family hindrance
