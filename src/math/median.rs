//! The median of a sample, as the stages take it: sorted by `f64::total_cmp`, the upper of the
//! two middle values of an even count.

/// The median of `values` (the upper middle one of an even count), `None` for none.
pub(crate) fn upper_median(mut values: Vec<f64>) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_upper_middle_value_of_the_sorted_sample() {
        assert_eq!(upper_median(vec![]), None);
        assert_eq!(upper_median(vec![3.0]), Some(3.0));
        assert_eq!(upper_median(vec![4.0, 1.0, 3.0, 2.0]), Some(3.0));
        assert_eq!(upper_median(vec![5.0, 1.0, 3.0]), Some(3.0));
    }
}
