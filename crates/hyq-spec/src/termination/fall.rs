//! Spec §6.3 (Fall): the robot has fallen when the trunk touched the
//! ground in **any** physics sub-step of the env step, not just the last:
//!
//! fell ⇔ ∃ sub-step s of the step: trunk_contact(s).
//!
//! The same fact is observation row 28 (`trunk_contact_flag`). The environment latches it across
//! the sub-steps; the rules receive it as one boolean.

/// Whether the trunk touched the ground in any sub-step, given each sub-step's contact fact.
pub fn fell_in_any_substep<I: IntoIterator<Item = bool>>(trunk_contact_per_substep: I) -> bool {
    trunk_contact_per_substep.into_iter().any(|touched| touched)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_touching_substep_is_a_fall() {
        assert!(!fell_in_any_substep([false; 10]));
        let mut contacts = [false; 10];
        contacts[3] = true;
        assert!(fell_in_any_substep(contacts));
        assert!(!fell_in_any_substep([]));
    }
}
