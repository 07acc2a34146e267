//! A plain text table: a header row, a rule, and right-aligned cells (left-aligned for the
//! columns marked so), each column as wide as its widest cell.

/// A table being built.
pub struct Table {
    headers: Vec<String>,
    left: Vec<bool>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column headers; a header starting with `<` is left-aligned (the `<`
    /// is not printed).
    pub fn new(headers: &[&str]) -> Self {
        Self {
            headers: headers
                .iter()
                .map(|h| h.trim_start_matches('<').to_owned())
                .collect(),
            left: headers.iter().map(|h| h.starts_with('<')).collect(),
            rows: Vec::new(),
        }
    }

    /// Adds a row (missing cells print empty, extra cells are dropped).
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// The table as text, one line per row, each ending in a newline.
    pub fn render(&self) -> String {
        let cell = |row: &[String], i: usize| row.get(i).map_or("", String::as_str).to_owned();
        let mut widths: Vec<usize> = self.headers.iter().map(|h| h.chars().count()).collect();
        for row in &self.rows {
            for (i, w) in widths.iter_mut().enumerate() {
                *w = (*w).max(cell(row, i).chars().count());
            }
        }
        let line = |cells: &[String]| {
            let mut out = String::new();
            for (i, (&w, &left)) in widths.iter().zip(&self.left).enumerate() {
                if i > 0 {
                    out.push_str("  ");
                }
                let c = cell(cells, i);
                if left {
                    out.push_str(&format!("{c:<w$}"));
                } else {
                    out.push_str(&format!("{c:>w$}"));
                }
            }
            out.trim_end().to_owned() + "\n"
        };
        let mut text = line(&self.headers);
        let rule: Vec<String> = widths.iter().map(|w| "-".repeat(*w)).collect();
        text.push_str(&line(&rule));
        for row in &self.rows {
            text.push_str(&line(row));
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::Table;

    #[test]
    fn columns_are_as_wide_as_their_widest_cell_and_aligned() {
        let mut t = Table::new(&["ep", "<end", "return"]);
        t.row(vec!["1".into(), "timeout".into(), "3.25".into()]);
        t.row(vec!["10".into(), "fell".into(), "-100.5".into()]);
        assert_eq!(
            t.render(),
            "ep  end      return\n\
             --  -------  ------\n \
             1  timeout    3.25\n\
             10  fell     -100.5\n"
        );
    }
}
