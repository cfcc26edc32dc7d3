//! A slide's widgets' computed numbers, as `lectern export --data` writes them (CSV: the
//! points of every path, a widget's own table, its readouts), and as the web player's test
//! hook returns them (`window.lectern.plotData()`, the same CSV as JSON): one code path, so a
//! browser test compares exactly what the desktop writes.

use super::SlideState;
use crate::deck::Slide;
use crate::widgets::Readout;

/// One widget's numbers: its place among the slide's widgets (1-based, in file order), its
/// CSV (`None` for a widget with nothing to plot) and its readouts.
pub struct WidgetData {
    pub ordinal: usize,
    pub csv: Option<String>,
    pub readouts: Vec<Readout>,
}

/// The numbers of every widget of `slide` in `state` (its widgets are made if need be).
pub fn slide_data(slide: &Slide, state: &mut SlideState) -> Vec<WidgetData> {
    state.ensure_widgets(slide);
    let mut out = Vec::new();
    for (k, (block, _)) in slide.widgets().into_iter().enumerate() {
        let Some(widget) = state.widget_at(&block) else {
            continue;
        };
        out.push(WidgetData {
            ordinal: k + 1,
            csv: widget.csv(),
            readouts: widget.readouts(),
        });
    }
    out
}

/// The slide's first widget with points, as JSON: `{"widget": K, "columns": [...], "rows":
/// [[...], ...]}`, each cell a number where the CSV has one (parsed from the very text
/// `export --data` writes, so the numbers are the same to the last bit), else a string;
/// `null` when no widget on the slide plots anything.
pub fn first_plot_json(slide: &Slide, state: &mut SlideState) -> String {
    let Some((ordinal, csv)) = slide_data(slide, state)
        .into_iter()
        .find_map(|w| w.csv.map(|c| (w.ordinal, c)))
    else {
        return "null".into();
    };
    csv_json(ordinal, &csv)
}

fn csv_json(ordinal: usize, csv: &str) -> String {
    let mut lines = csv.lines();
    let columns: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let rows: Vec<Vec<serde_json::Value>> = lines
        .filter(|l| !l.is_empty())
        .map(|l| {
            l.split(',')
                .map(|cell| match cell.parse::<f64>() {
                    Ok(v) if v.is_finite() => serde_json::Value::from(v),
                    _ => serde_json::Value::from(cell),
                })
                .collect()
        })
        .collect();
    serde_json::json!({ "widget": ordinal, "columns": columns, "rows": rows }).to_string()
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_json_holds_the_csv_numbers_exactly() {
        let csv = "series,t,x\neuler,0,1\neuler,0.1,0.30000000000000004\nexact,0.1,NaN\n";
        let json: serde_json::Value = serde_json::from_str(&super::csv_json(2, csv)).unwrap();
        assert_eq!(json["widget"], 2);
        assert_eq!(json["columns"][2], "x");
        assert_eq!(json["rows"][1][2].as_f64(), Some(0.1 + 0.2));
        assert_eq!(json["rows"][2][2], "NaN");
        assert_eq!(json["rows"].as_array().unwrap().len(), 3);
    }
}
