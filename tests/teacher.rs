//! raytree as a teacher uses it (issue 28): grading a class from a CSV file, validating a
//! folder of lessons, handing out homework that differs per student, and the JSON a script
//! reads. Every expected number comes from a lesson's hand-worked README or is worked out here.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

/// A scratch folder of this test binary; progress goes to its own data folder.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir()
        .join(format!("raytree-teacher-{}", std::process::id()))
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.parent().unwrap()).unwrap();
    dir
}

fn raytree_in(data: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("RAYTREE_DATA", data)
        .env("NO_COLOR", "1")
        .output()
        .unwrap()
}

fn raytree(args: &[&str]) -> Output {
    raytree_in(&scratch_data(), args)
}

/// `raytree grade LESSON --answers SHEET --format json`, which must succeed, as JSON.
fn grade_json(lesson: &str, sheet: &Path) -> Value {
    let o = raytree(&[
        "grade",
        lesson,
        "--answers",
        sheet.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}{}", out(&o), err(&o));
    serde_json::from_str(&out(&o)).unwrap_or_else(|e| panic!("{e}: {}", out(&o)))
}

/// A class's answers, `rows` of CSV, written as c.csv in a scratch folder of its own.
fn answer_sheet(name: &str, rows: impl AsRef<[u8]>) -> PathBuf {
    let dir = scratch(name);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("c.csv");
    std::fs::write(&file, rows).unwrap();
    file
}

fn scratch_data() -> PathBuf {
    std::env::temp_dir().join(format!("raytree-teacher-{}-data", std::process::id()))
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The `**Answer (ID):** value` lines of a lesson's README.
fn readme_answers(lesson: &str) -> Vec<(String, String)> {
    let text =
        std::fs::read_to_string(Path::new("lessons").join(lesson).join("README.md")).unwrap();
    text.lines()
        .filter_map(|l| {
            let rest = l.trim().strip_prefix("**Answer (")?;
            let (id, v) = rest.split_once("):**")?;
            Some((id.to_string(), v.trim().to_string()))
        })
        .collect()
}

/// A wrong answer of the same kind: every number moved by a half and more.
fn spoil(answer: &str) -> String {
    answer
        .split(',')
        .map(|x| format!("{}", x.trim().parse::<f64>().unwrap() + 0.75))
        .collect::<Vec<_>>()
        .join(", ")
}

fn csv_field(s: &str) -> String {
    if s.contains(',') {
        format!("\"{s}\"")
    } else {
        s.to_string()
    }
}

/// A class of 30 answers lesson 05: student k gets exercise j wrong when (3k + 2j) % 7 == 0,
/// leaves it out when (k + j) % 10 == 3, and answers it right otherwise (the README's
/// hand-worked value). Three rows are broken on purpose and one student changes an answer.
/// The report must give every student the score the seeding gives, and name the broken rows
/// by their line.
#[test]
fn a_class_of_30_is_graded_as_seeded() {
    let dir = scratch("class");
    std::fs::create_dir_all(&dir).unwrap();
    let answers = readme_answers("05-reflection");
    assert_eq!(answers.len(), 11);
    let mut csv = String::from("student,exercise,answer\n");
    let mut line = 1;
    let mut expected_scores = vec![];
    let mut expected_wrong: Vec<(String, String)> = vec![];
    let mut broken_lines = vec![];
    for k in 0..30 {
        let student = format!("student{k:02}");
        let mut score = 0;
        for (j, (id, right)) in answers.iter().enumerate() {
            if (k + j) % 10 == 3 {
                expected_wrong.push((student.clone(), id.clone()));
                continue;
            }
            let wrong = (3 * k + 2 * j) % 7 == 0;
            let given = if wrong { spoil(right) } else { right.clone() };
            if wrong {
                expected_wrong.push((student.clone(), id.clone()));
            } else {
                score += 1;
            }
            csv.push_str(&format!("{student},{id},{}\n", csv_field(&given)));
            line += 1;
        }
        expected_scores.push((student, score));
        if k == 5 {
            csv.push_str("student05\n");
            line += 1;
            broken_lines.push(line);
        }
        if k == 11 {
            csv.push_str("student11,no-such-exercise,1\n");
            line += 1;
            broken_lines.push(line);
        }
        if k == 17 {
            csv.push_str(",mirror-local,0.23\n");
            line += 1;
            broken_lines.push(line);
        }
    }
    // student29 first answered mirror-local wrong, then right: the later row counts.
    let (_, mirror) = answers.iter().find(|(id, _)| id == "mirror-local").unwrap();
    let k = 29;
    let j = answers
        .iter()
        .position(|(id, _)| id == "mirror-local")
        .unwrap();
    assert!(
        (3 * k + 2 * j) % 7 != 0 && (k + j) % 10 != 3,
        "seeded right already"
    );
    csv.push_str(&format!("student29,mirror-local,{mirror}\n"));
    line += 1;
    let _ = line;
    let file = dir.join("answers.csv");
    std::fs::write(&file, &csv).unwrap();

    let o = raytree(&[
        "grade",
        "lessons/05-reflection",
        "--answers",
        file.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", err(&o));
    let report: Value = serde_json::from_str(&out(&o)).unwrap();
    assert!(report["raytree_version"].is_string());
    let students = report["students"].as_array().unwrap();
    assert_eq!(students.len(), 30);
    for (s, (name, score)) in students.iter().zip(&expected_scores) {
        assert_eq!(s["student"], name.as_str());
        assert_eq!(s["score"], *score as u64, "{name}");
        assert_eq!(s["total"], 11);
        for e in s["exercises"].as_array().unwrap() {
            let wrong = expected_wrong
                .iter()
                .any(|(st, ex)| st == name && e["exercise"] == ex.as_str());
            assert_eq!(e["correct"], !wrong, "{name} {}", e["exercise"]);
            assert!(e.get("answer").is_some() && e.get("hint").is_some());
        }
    }
    let problems: Vec<u64> = report["problems"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["line"].as_u64().unwrap())
        .collect();
    for l in &broken_lines {
        assert!(
            problems.contains(&(*l as u64)),
            "line {l} not reported: {problems:?}"
        );
    }
    // The replaced answer is reported too (four problems in all).
    assert_eq!(problems.len(), broken_lines.len() + 1, "{problems:?}");
    for l in &broken_lines {
        assert!(
            err(&o).contains(&format!("answers.csv:{l}:")),
            "{}",
            err(&o)
        );
    }

    // The same report as text and as CSV.
    let text = out(&raytree(&[
        "grade",
        "lessons/05-reflection",
        "--answers",
        file.to_str().unwrap(),
    ]));
    let (name, score) = &expected_scores[7];
    assert!(text.contains(&format!("{name}  {score}/11")), "{text}");
    assert!(text.contains("rows not graded:"));
    let csv_out = out(&raytree(&[
        "grade",
        "lessons/05-reflection",
        "--answers",
        file.to_str().unwrap(),
        "--format",
        "csv",
    ]));
    assert!(csv_out.starts_with("student,exercise,answer,correct,expected,hint\n"));
    assert_eq!(csv_out.lines().count(), 1 + 30 * 11);
}

/// A copy of lesson 03 whose README states one answer wrong (0.093 for the Blinn specular term,
/// 0.093623 by hand) fails validation, naming that exercise and no other; the shipped lessons pass.
/// Every `**Answer (ID):**` line of a README is compared, not only the first of an id: a
/// second line that says otherwise is named at its line of README.md, the first still agreeing.
#[test]
fn validation_compares_every_answer_line_of_an_exercise() {
    let dir = scratch("validate-twice/03-local-illumination");
    copy_lesson("03-local-illumination", &dir);
    let readme = dir.join("README.md");
    let text = std::fs::read_to_string(&readme).unwrap();
    let line = "**Answer (specular-blinn):** 0.093623";
    let at = text.lines().position(|l| l.trim() == line).unwrap() + 1;
    std::fs::write(
        &readme,
        text.replace(line, &format!("{line}\n**Answer (specular-blinn):** 0.9")),
    )
    .unwrap();
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", out(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 1, "{report}");
    assert!(
        problems[0].contains(&format!(
            "{}:{}: exercise `specular-blinn`: the README says 0.9, raytree computes 0.093623",
            readme.display(),
            at + 1
        )),
        "{report}"
    );
}

#[test]
fn validation_names_a_corrupted_readme_answer() {
    let dir = scratch("validate/03-local-illumination");
    copy_lesson("03-local-illumination", &dir);
    let readme = dir.join("README.md");
    let text = std::fs::read_to_string(&readme).unwrap();
    let corrupted = text.replace(
        "**Answer (specular-blinn):** 0.093623",
        "**Answer (specular-blinn):** 0.093",
    );
    assert_ne!(text, corrupted);
    std::fs::write(&readme, corrupted).unwrap();
    let o = raytree(&[
        "lessons",
        "validate",
        dir.parent().unwrap().to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", out(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 1, "{report}");
    assert!(problems[0].contains("specular-blinn"), "{report}");
    assert!(problems[0].contains("0.093623"), "{report}");

    let shipped = raytree(&["lessons", "validate", "lessons"]);
    assert!(shipped.status.success(), "{}", out(&shipped));
    let lessons = std::fs::read_dir("lessons")
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().join("exercises.yaml").is_file())
        .count();
    assert!(
        out(&shipped).starts_with(&format!("ok: {lessons} lessons")),
        "{}",
        out(&shipped)
    );
}

/// The light position, kd and ks a homework scene of lesson 03 was given.
fn lesson03_values(scene: &str) -> ([f64; 3], f64, f64) {
    let light = scene.lines().find(|l| l.contains("name: L")).unwrap();
    let point = light
        .split("point: [")
        .nth(1)
        .unwrap()
        .split(']')
        .next()
        .unwrap();
    let p: Vec<f64> = point
        .split(',')
        .map(|x| x.trim().parse().unwrap())
        .collect();
    let plastic = scene
        .lines()
        .find(|l| l.trim_start().starts_with("plastic:"))
        .unwrap();
    let field = |k: &str| -> f64 {
        plastic
            .split(&format!(" {k}: "))
            .nth(1)
            .unwrap()
            .split([',', ' '])
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    ([p[0], p[1], p[2]], field("kd"), field("ks"))
}

/// Lesson 03's diffuse term at P = (0, 0, −1), n = (0, 0, −1), O = 0.8, IL = 1,
/// attenuation [1, 0.1, 0.01], worked out from the light position and kd.
fn diffuse_by_hand([lx, ly, lz]: [f64; 3], kd: f64) -> f64 {
    let to = [lx, ly, lz + 1.0];
    let d = (to[0] * to[0] + to[1] * to[1] + to[2] * to[2]).sqrt();
    let n_dot_l = -to[2] / d;
    let fatt = 1.0 / (1.0 + 0.1 * d + 0.01 * d * d);
    fatt * kd * 0.8 * n_dot_l
}

/// Two students' homework of lesson 03 differ; each one's hand-worked diffuse term is right
/// for their own homework (checked in their folder, with --student, and by grade) and wrong for
/// the other's. The same ID always gets the same folder.
#[test]
fn two_students_homework_differ_and_grade_against_their_own_values() {
    let root = scratch("homework");
    let (alice, bob, again) = (
        root.join("alice"),
        root.join("bob"),
        root.join("alice-again"),
    );
    for (student, dir) in [("alice", &alice), ("bob", &bob), ("alice", &again)] {
        let o = raytree(&[
            "homework",
            "lessons/03-local-illumination",
            "--student",
            student,
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", err(&o));
    }
    for f in [
        "scene.yaml",
        "phong.yaml",
        "color.yaml",
        "exercises.yaml",
        "README.md",
    ] {
        assert_eq!(
            std::fs::read(alice.join(f)).unwrap(),
            std::fs::read(again.join(f)).unwrap(),
            "{f} differs for the same student"
        );
    }
    let a_scene = std::fs::read_to_string(alice.join("scene.yaml")).unwrap();
    let b_scene = std::fs::read_to_string(bob.join("scene.yaml")).unwrap();
    assert_ne!(a_scene, b_scene);
    let readme = std::fs::read_to_string(alice.join("README.md")).unwrap();
    assert!(
        !readme.contains("**Answer ("),
        "the homework README gives answers away"
    );
    assert!(readme.contains("diffuse"));

    let (la, kda, _) = lesson03_values(&a_scene);
    let (lb, kdb, _) = lesson03_values(&b_scene);
    let (da, db) = (diffuse_by_hand(la, kda), diffuse_by_hand(lb, kdb));
    assert!(
        (da - db).abs() > 0.01 * da.max(db),
        "{da} {db}: too close to tell apart"
    );
    let (da, db) = (format!("{da:.6}"), format!("{db:.6}"));

    let check = |dir: &Path, answer: &str| {
        raytree(&[
            "check",
            dir.to_str().unwrap(),
            "--exercise",
            "diffuse",
            "--answer",
            answer,
        ])
        .status
        .code()
    };
    assert_eq!(check(&alice, &da), Some(0));
    assert_eq!(check(&alice, &db), Some(1));
    assert_eq!(check(&bob, &db), Some(0));
    assert_eq!(check(&bob, &da), Some(1));
    let with_id = |student: &str, answer: &str| {
        raytree(&[
            "check",
            "lessons/03-local-illumination",
            "--student",
            student,
            "--exercise",
            "diffuse",
            "--answer",
            answer,
        ])
        .status
        .code()
    };
    assert_eq!(with_id("alice", &da), Some(0));
    assert_eq!(with_id("bob", &da), Some(1));

    let csv = root.join("answers.csv");
    std::fs::write(
        &csv,
        format!("alice,diffuse,{da}\nbob,diffuse,{db}\ncarol,diffuse,{da}\n"),
    )
    .unwrap();
    let report = grade_json("lessons/03-local-illumination", &csv);
    let right = |k: usize| {
        report["students"][k]["exercises"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["exercise"] == "diffuse")
            .unwrap()["correct"]
            .clone()
    };
    assert_eq!(right(0), true, "alice");
    assert_eq!(right(1), true, "bob");
    assert_eq!(right(2), false, "carol copied alice's answer");
    let carol = report["students"][2]["exercises"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["exercise"] == "diffuse")
        .unwrap()["hint"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(carol.contains("alice's answer"), "{carol}");

    // Alice's folder holds alice's values only: asked for its own student it checks as
    // before; asked for bob's (check, grade or another homework) it refuses and names the
    // lesson to give instead, where it graded every student against alice's numbers.
    let in_folder = |student: &str, answer: &str| {
        raytree(&[
            "check",
            alice.to_str().unwrap(),
            "--student",
            student,
            "--exercise",
            "diffuse",
            "--answer",
            answer,
        ])
    };
    assert_eq!(in_folder("alice", &da).status.code(), Some(0));
    let refused = [
        in_folder("bob", &da),
        raytree(&[
            "grade",
            alice.to_str().unwrap(),
            "--answers",
            csv.to_str().unwrap(),
        ]),
        raytree(&[
            "homework",
            alice.to_str().unwrap(),
            "--student",
            "bob",
            "-o",
            root.join("nested").to_str().unwrap(),
        ]),
    ];
    for o in refused {
        assert_eq!(o.status.code(), Some(2), "{}", out(&o));
        let e = err(&o);
        assert!(
            e.contains("alice's homework of lesson 03-local-illumination")
                && e.contains("bob's values")
                && e.contains("give `03-local-illumination`"),
            "{e}"
        );
    }
    assert!(!root.join("nested").exists());
}

/// `check` of lesson 05's mirror-local (the mirror's local term, 0.23 by hand) with `answer`,
/// progress kept in `data`.
fn check_mirror_local(data: &Path, answer: &str) -> Output {
    let args = [
        "check",
        "lessons/05-reflection",
        "--exercise",
        "mirror-local",
    ];
    raytree_in(data, &[&args[..], &["--answer", answer]].concat())
}

/// `check --format json` carries the contract's fields, and a right answer is remembered:
/// `lessons --format json` marks it solved, in the data folder RAYTREE_DATA names.
#[test]
fn check_json_and_progress() {
    let data = scratch("progress-data");
    let o = raytree_in(
        &data,
        &[
            "check",
            "lessons/05-reflection",
            "--exercise",
            "mirror-local",
            "--answer",
            "0.3",
            "--format",
            "json",
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let v: Value = serde_json::from_str(&out(&o)).unwrap();
    for field in [
        "correct",
        "answer",
        "expected",
        "tolerance",
        "hint",
        "raytree_version",
    ] {
        assert!(v.get(field).is_some(), "{field} missing: {v}");
    }
    assert_eq!(v["correct"], false);
    // The mirror's local term, 0.23 by hand (README).
    assert!(
        (v["expected"].as_f64().unwrap() - 0.23).abs() < 1e-12,
        "{v}"
    );
    let solved = |data: &Path| -> Vec<String> {
        let o = raytree_in(data, &["lessons", "--format", "json"]);
        let v: Value = serde_json::from_str(&out(&o)).unwrap();
        v["lessons"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|l| l["id"] == "05-reflection")
            .flat_map(|l| l["exercises"].as_array().unwrap().clone())
            .filter(|e| e["solved"] == true)
            .map(|e| e["id"].as_str().unwrap().to_string())
            .collect()
    };
    assert!(solved(&data).is_empty());
    let o = check_mirror_local(&data, "0.23");
    assert!(o.status.success());
    assert_eq!(solved(&data), vec!["mirror-local".to_string()]);
    let text = out(&raytree_in(&data, &["lessons"]));
    assert!(text.contains("✓ mirror-local"), "{text}");
    assert!(text.contains("(1/11 done)"), "{text}");
}

/// raytree run in `cwd` (a folder without `lessons/`, so the built-in lessons are used), with
/// its own data and cache folders.
fn raytree_built_in(cwd: &Path, data: &Path, cache: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .current_dir(cwd)
        .env("RAYTREE_DATA", data)
        .env("RAYTREE_CACHE", cache)
        .env_remove("RAYTREE_LESSONS")
        .env("NO_COLOR", "1")
        .output()
        .unwrap()
}

/// A built-in lesson's marks belong to the lesson, not to the cache folder its copy is written
/// to: a new cache folder (a cleared cache, a new version) keeps them, and marks an earlier
/// version kept under its copy's folder still count. An answer checked for another student
/// (`--student`, grading) does not mark the checker's own lesson.
#[test]
fn progress_is_kept_by_lesson_not_by_cache_folder() {
    let root = scratch("built-in-progress");
    let (cwd, data) = (root.join("home"), root.join("data"));
    std::fs::create_dir_all(&cwd).unwrap();
    let done = |cache: &str| {
        let o = raytree_built_in(
            &cwd,
            &data,
            &root.join(cache),
            &["lessons", "05-reflection"],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out(&o).lines().next().unwrap_or_default().to_string()
    };
    let check = |args: &[&str]| {
        let mut all = vec!["check", "05-reflection", "--exercise", "mirror-local"];
        all.extend_from_slice(args);
        raytree_built_in(&cwd, &data, &root.join("cache-1"), &all)
    };
    assert!(check(&["--answer", "0.23", "--student", "s1"])
        .status
        .success());
    assert!(
        done("cache-1").contains("(0/11 done)"),
        "{}",
        done("cache-1")
    );
    assert!(check(&["--answer", "0.23"]).status.success());
    assert!(
        done("cache-1").contains("(1/11 done)"),
        "{}",
        done("cache-1")
    );
    assert!(
        done("cache-2").contains("(1/11 done)"),
        "{}",
        done("cache-2")
    );

    // An earlier version's mark, under its copy's folder in the cache.
    let old_copy = root
        .join("cache-2")
        .join("lessons-0.0.1-0000000000000000")
        .join("05-reflection");
    std::fs::create_dir_all(&old_copy).unwrap();
    let old_key = std::fs::canonicalize(&old_copy)
        .unwrap()
        .display()
        .to_string();
    let file = data.join("progress.json");
    let old = serde_json::json!({ "lessons": { old_key: ["pixel-intensity"] } });
    std::fs::write(&file, old.to_string()).unwrap();
    assert!(
        done("cache-2").contains("(1/11 done)"),
        "{}",
        done("cache-2")
    );
    let o = raytree_built_in(
        &cwd,
        &data,
        &root.join("cache-2"),
        &["lessons", "05-reflection"],
    );
    assert!(out(&o).contains("✓ pixel-intensity"), "{}", out(&o));
}

/// A progress file that does not read as progress is not written over by the next right
/// answer: the check still passes, and says why nothing was saved.
#[test]
fn a_corrupt_progress_file_is_left_alone_with_a_warning() {
    let data = scratch("corrupt-progress");
    std::fs::create_dir_all(&data).unwrap();
    let file = data.join("progress.json");
    std::fs::write(&file, "{not json").unwrap();
    let o = check_mirror_local(&data, "0.23");
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("progress not saved") && err.contains("not a progress file"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "{not json");
}

/// A lesson with `solutions: hidden` only says right or wrong: no hint, which would name the
/// kind of the answer (past the limiting angle there is no refracted ray) or the mistake.
#[test]
fn hidden_solutions_give_no_hint() {
    let dir = scratch("hidden-hint").join("06-refraction");
    copy_lesson("06-refraction", &dir);
    let exercises = std::fs::read_to_string(dir.join("exercises.yaml")).unwrap();
    std::fs::write(
        dir.join("exercises.yaml"),
        exercises.replacen("exercises:", "solutions: hidden\nexercises:", 1),
    )
    .unwrap();
    let d = dir.to_str().unwrap();
    let o = raytree(&[
        "check",
        d,
        "--exercise",
        "beyond-critical",
        "--answer",
        "0, 1, 0",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let said = out(&o);
    assert!(said.contains("wrong"), "{said}");
    assert!(!said.contains("hint") && !said.contains("tir"), "{said}");
    // The same lesson with its solutions shown hints at it.
    let o = raytree(&[
        "check",
        "06-refraction",
        "--exercise",
        "beyond-critical",
        "--answer",
        "0, 1, 0",
    ]);
    assert!(out(&o).contains("answer tir"), "{}", out(&o));
}

/// A lesson with `solutions: hidden` refuses --explain (a usage error) but checks answers.
#[test]
fn hidden_solutions_are_not_explained() {
    let dir = scratch("hidden");
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["scene.yaml", "README.md"] {
        std::fs::copy(Path::new("lessons/05-reflection").join(f), dir.join(f)).unwrap();
    }
    let exercises = std::fs::read_to_string("lessons/05-reflection/exercises.yaml").unwrap();
    std::fs::write(
        dir.join("exercises.yaml"),
        exercises.replacen("exercises:", "solutions: hidden\nexercises:", 1),
    )
    .unwrap();
    let d = dir.to_str().unwrap();
    let o = raytree(&["check", d, "--exercise", "mirror-local", "--explain"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("hidden"), "{}", err(&o));
    let o = raytree(&["check", d, "--exercise", "mirror-local", "--answer", "0.23"]);
    assert!(o.status.success());
    let plain = out(&o);

    // With an answer, --explain checks it as without, then says why no derivation follows.
    let o = raytree(&[
        "check",
        d,
        "--exercise",
        "mirror-local",
        "--answer",
        "0.23",
        "--explain",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}{}", out(&o), err(&o));
    let text = out(&o);
    assert!(text.starts_with(&plain), "{text}");
    let last = text.lines().last().unwrap();
    assert!(last.contains("worked solution is hidden"), "{text}");
    let o = raytree(&[
        "check",
        d,
        "--exercise",
        "mirror-local",
        "--answer",
        "0.5",
        "--explain",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let wrong = out(&raytree(&[
        "check",
        d,
        "--exercise",
        "mirror-local",
        "--answer",
        "0.5",
    ]));
    assert!(out(&o).starts_with(&wrong), "{}", out(&o));
    assert!(out(&o).contains("worked solution is hidden"), "{}", out(&o));
    // Nor does the JSON give a wrong answer the expected one; a right one it confirms.
    let json = |answer: &str| -> Value {
        let args = ["check", d, "--exercise", "mirror-local", "--answer", answer];
        serde_json::from_str(&out(&raytree(&[&args[..], &["--format", "json"]].concat()))).unwrap()
    };
    let v = json("0.5");
    assert_eq!(v["correct"], false);
    assert!(v["expected"].is_null(), "{v}");
    // Nor its allowance: 0.1 % of the answer would give the answer away.
    assert!(v["tolerance"].is_null(), "{v}");
    assert!(v["tolerance_rule"].is_object(), "{v}");
    let right = json("0.23");
    assert!((right["expected"].as_f64().unwrap() - 0.23).abs() < 1e-12);
    assert!(
        (right["tolerance"].as_f64().unwrap() - 0.23e-3).abs() < 1e-12,
        "{right}"
    );
}

/// The rows a new user got wrong: a missing answer field, a quote never closed, an answer with
/// unquoted commas. Each is named under "rows not graded" with its line and why, and none is
/// graded; the row after the open quote still is.
#[test]
fn rows_that_do_not_read_are_not_graded() {
    let file = answer_sheet(
        "malformed",
        "s1,pixel-p\ns5,pixel-p,\"0.87\ns6,pixel-p,0.6,0.8\ns7,pixel-p,0.87\n",
    );
    let f = file.to_str().unwrap();
    let o = raytree(&[
        "grade",
        "08-pixel-intensity",
        "--answers",
        f,
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", err(&o));
    let report: Value = serde_json::from_str(&out(&o)).unwrap();
    let students: Vec<&str> = report["students"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["student"].as_str().unwrap())
        .collect();
    assert_eq!(students, ["s7"]);
    let problems: Vec<(u64, &str)> = report["problems"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["line"].as_u64().unwrap(), p["message"].as_str().unwrap()))
        .collect();
    assert_eq!(problems.len(), 3, "{problems:?}");
    let why: Vec<u64> = problems.iter().map(|(l, _)| *l).collect();
    assert_eq!(why, [1, 2, 3]);
    assert!(problems[0].1.contains("2 fields"), "{problems:?}");
    assert!(problems[1].1.contains("never closed"), "{problems:?}");
    assert!(problems[2].1.contains("4 fields"), "{problems:?}");

    let text = out(&raytree(&["grade", "08-pixel-intensity", "--answers", f]));
    let (_, not_graded) = text.split_once("rows not graded:").expect(&text);
    for line in 1..=3 {
        assert!(not_graded.contains(&format!("c.csv:{line}: ")), "{text}");
    }
    for student in ["s1", "s5", "s6"] {
        assert!(
            !text.lines().any(|l| l.starts_with(student)),
            "{student} graded: {text}"
        );
    }
}

/// A sheet where no row names an exercise of the lesson (another lesson's answers) grades
/// nobody: `grade` says so and exits 1, so a script cannot take it for an empty class.
#[test]
fn a_sheet_where_nothing_is_graded_exits_1() {
    let file = answer_sheet("nothing-graded", "s1,tangent-t,8\ns2,no-such-exercise,1\n");
    let o = raytree(&[
        "grade",
        "08-pixel-intensity",
        "--answers",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(err(&o).contains("no answer graded"), "{}", err(&o));
}

/// Answers, READMEs and exercise files are read within a budget, and a device is refused at
/// once: /dev/zero given as the answers, or linked as a lesson's README or exercises.yaml, is
/// never read without end (it would take all the memory there is before failing).
#[cfg(unix)]
#[test]
fn a_device_is_refused_as_answers_and_as_a_lessons_readme() {
    let o = raytree(&["grade", "03-local-illumination", "--answers", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(
        err(&o).contains("/dev/zero: not a regular file"),
        "{}",
        err(&o)
    );

    let root = scratch("device-readme");
    let dir = root.join("02-intersection");
    std::fs::create_dir_all(&dir).unwrap();
    for f in std::fs::read_dir("lessons/02-intersection").unwrap() {
        let f = f.unwrap();
        if f.file_name() != "README.md" && f.path().is_file() {
            std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
        }
    }
    std::os::unix::fs::symlink("/dev/zero", dir.join("README.md")).unwrap();
    let o = raytree(&["lessons", "validate", root.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", out(&o));
    let report = out(&o);
    assert!(
        report.contains("README.md: cannot read: not a regular file"),
        "{report}"
    );
    assert!(!report.contains("states no answer"), "{report}");

    // The folder is still a lesson with its exercises.yaml a device: named, not passed over.
    std::fs::remove_file(dir.join("README.md")).unwrap();
    std::fs::remove_file(dir.join("exercises.yaml")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("exercises.yaml")).unwrap();
    let o = raytree(&["lessons", "validate", root.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let report = out(&o);
    assert!(
        report.contains("exercises.yaml: cannot read: not a regular file"),
        "{report}"
    );
}

/// A lesson whose exercises.yaml does not read is named once by file:line:column, and the
/// summary says that it could not be read, not that it disagrees.
#[test]
fn a_lesson_that_does_not_read_is_reported_as_such() {
    let root = scratch("unreadable");
    for name in ["01-camera", "02-broken"] {
        let dir = root.join(name);
        std::fs::create_dir_all(&dir).unwrap();
        for f in std::fs::read_dir("lessons/01-camera").unwrap() {
            let f = f.unwrap();
            std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
        }
    }
    let broken = root.join("02-broken/exercises.yaml");
    let text = std::fs::read_to_string(&broken).unwrap();
    let at = text.find("ask: window_point").unwrap();
    let line = text[..at].matches('\n').count() + 1;
    let column = at - text[..at].rfind('\n').unwrap() + "ask: ".len();
    std::fs::write(
        &broken,
        text.replacen("ask: window_point", "ask: colour", 1),
    )
    .unwrap();

    let o = raytree(&["lessons", "validate", root.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", out(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 1, "{report}");
    let location = format!("02-broken/exercises.yaml:{line}:{column}: ");
    assert!(problems[0].contains(&location), "{report}");
    assert!(problems[0].contains("colour"), "{report}");
    assert!(!problems[0].contains("column"), "{report}");
    let summary = report.lines().last().unwrap();
    assert!(
        summary.starts_with("1 lesson could not be read; 1 lesson checked"),
        "{report}"
    );
    assert!(!summary.contains("disagreement"), "{report}");
}

/// Names and answers come from the class's file: the report shows their control characters
/// escaped, so a name cannot clear the teacher's terminal or fake a line of the report; so do
/// the JSON and the CSV forms.
#[test]
fn the_grade_report_shows_control_characters_escaped() {
    let file = answer_sheet("control", "s1\u{1b}[2J,pixel-p,0.5\u{7}\n");
    for format in ["text", "json", "csv"] {
        let o = raytree(&[
            "grade",
            "08-pixel-intensity",
            "--answers",
            file.to_str().unwrap(),
            "--format",
            format,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(
            !out.contains('\u{1b}') && !out.contains('\u{7}'),
            "{format}: {out:?}"
        );
        assert!(
            out.contains("s1\\u{1b}[2J") || out.contains("s1\\u001b[2J"),
            "{format}: {out}"
        );
    }
}

/// A homework folder holds the student's values, never the lesson's answers: lesson 08 ships a
/// figure drawn from its own scene (its title quotes the pixel's intensity), and no file of a
/// student's folder may contain an answer the lesson's README works out by hand.
/// Every file the homework README names is in the folder.
#[test]
fn a_homework_folder_holds_none_of_the_lessons_answers_and_every_file_its_readme_names() {
    let root = scratch("homework-answers");
    for lesson in ["08-pixel-intensity"] {
        let dir = root.join(lesson);
        let o = raytree(&[
            "homework",
            lesson,
            "--student",
            "s1234",
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", err(&o));
        let readme = std::fs::read_to_string(format!("lessons/{lesson}/README.md")).unwrap();
        // The hand-worked answers' numbers with enough digits to be telling (not a "0" of a
        // direction or a small figure a scene may hold for another reason).
        let answers: Vec<&str> = readme
            .lines()
            .filter_map(|l| l.trim().strip_prefix("**Answer (")?.split_once("):**"))
            .flat_map(|(_, value)| value.split(','))
            .map(str::trim)
            .filter(|v| v.len() >= 7)
            .collect();
        assert!(answers.len() >= 5, "{lesson}: {answers:?}");
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
            for a in &answers {
                assert!(
                    !text.contains(a),
                    "{}: holds the lesson's answer {a}",
                    path.display()
                );
            }
        }
        let homework = std::fs::read_to_string(dir.join("README.md")).unwrap();
        let links = homework
            .split("](")
            .skip(1)
            .filter_map(|s| s.split(')').next());
        let quoted = homework.split('`').skip(1).step_by(2).filter(|s| {
            [".yaml", ".svg", ".png", ".obj", ".exr"]
                .iter()
                .any(|e| s.ends_with(e))
        });
        for name in links.chain(quoted) {
            assert!(
                dir.join(name).is_file(),
                "{lesson}: the homework README names {name}, not in the folder"
            );
        }
    }
}

/// The value a scene gives a `vary:` path: map keys, and list items by their `name`.
fn at_path<'a>(scene: &'a Value, path: &str) -> Option<&'a Value> {
    path.split('.').try_fold(scene, |node, key| match node {
        Value::Object(map) => map.get(key),
        Value::Array(items) => items.iter().find(|i| i["name"] == key),
        _ => None,
    })
}

/// A value as numbers: `1.5` is [1.5], `[0, 4, -4]` is [0, 4, -4].
fn value_numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(value_numbers).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap()],
        _ => vec![],
    }
}

/// The numbers a text writes, in order: "(0.8, -0.6, 0) at 1.5." is 0.8, −0.6, 0, 1.5. Digits
/// that end a word (`h2`, `lamp2.yaml`) are not numbers; `-` and `−` before a digit are its
/// sign.
fn numbers(text: &str) -> Vec<f64> {
    let chars: Vec<char> = text.chars().collect();
    let digit = |k: usize| chars.get(k).is_some_and(char::is_ascii_digit);
    let mut out = vec![];
    let mut i = 0;
    while i < chars.len() {
        let sign = matches!(chars[i], '-' | '−') && digit(i + 1);
        let in_word = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        if (sign || digit(i)) && !in_word {
            let mut j = i + 1;
            while digit(j) || (chars.get(j) == Some(&'.') && digit(j + 1)) {
                j += 1;
            }
            let written: String = chars[i..j].iter().collect();
            out.push(written.replace('−', "-").parse().unwrap());
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// Texts of a lesson's questions that write one of its varied values for another quantity:
/// a direction, or a coefficient the lesson does not vary.
const NOT_VARIED_QUOTES: &[(&str, &str)] = &[
    // The ray's direction, not the floor's kd 0.8.
    ("06-refraction", "direction (0.8, 0.6, 0)"),
    // ka and kr, ks, kt of the lecture's exercise, not the varied ambient 0.3 and kd 0.2, 0.3.
    ("08-pixel-intensity", "ka 0.2"),
    ("08-pixel-intensity", "kr = ks = 0.3, kt 0.3"),
];

/// A homework's questions quote the student's values, never the lesson's: for every lesson
/// with `vary:` and every value a varied path has in the lesson's scene files, a student who
/// did not draw that value finds that number (or that vector's numbers in a row) nowhere in
/// the questions of their README, except where the text is known to mean another quantity.
#[test]
fn a_homework_readme_quotes_none_of_the_values_its_lesson_varies() {
    let root = scratch("homework-quotes");
    let mut lessons = 0;
    let mut entries: Vec<_> = std::fs::read_dir("lessons")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("exercises.yaml").is_file())
        .collect();
    entries.sort();
    for lesson in entries {
        let name = lesson.file_name().unwrap().to_string_lossy().into_owned();
        let read = |p: &Path| -> Value {
            serde_saphyr::from_str(&std::fs::read_to_string(p).unwrap())
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
        };
        let exercises = read(&lesson.join("exercises.yaml"));
        let Some(vary) = exercises["vary"].as_object().filter(|v| !v.is_empty()) else {
            continue;
        };
        lessons += 1;
        // Every value each varied path has in the lesson's scenes.
        let scenes: Vec<Value> = std::fs::read_dir(&lesson)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.extension().is_some_and(|e| e == "yaml") && !p.ends_with("exercises.yaml")
            })
            .map(|p| read(&p))
            .collect();
        let lesson_values: Vec<(&String, Vec<Vec<f64>>)> = vary
            .keys()
            .map(|path| {
                let mut values: Vec<Vec<f64>> = vec![];
                for v in scenes.iter().filter_map(|s| at_path(s, path)) {
                    let v = value_numbers(v);
                    if !values.contains(&v) {
                        values.push(v);
                    }
                }
                assert!(!values.is_empty(), "{name}: no scene writes {path}");
                (path, values)
            })
            .collect();
        let mut checked: Vec<&String> = vec![];
        for student in ["s1234", "alice", "bob"] {
            let dir = root.join(format!("{name}-{student}"));
            let o = raytree(&[
                "homework",
                lesson.to_str().unwrap(),
                "--student",
                student,
                "-o",
                dir.to_str().unwrap(),
            ]);
            assert!(o.status.success(), "{name} {student}: {}", err(&o));
            let readme = std::fs::read_to_string(dir.join("README.md")).unwrap();
            let mut questions = readme
                .split("## Exercises")
                .nth(1)
                .and_then(|s| s.split("## Answering").next())
                .unwrap_or_else(|| panic!("{name}: no exercises in\n{readme}"))
                .to_string();
            for (of, quote) in NOT_VARIED_QUOTES.iter().filter(|(l, _)| *l == name) {
                assert!(questions.contains(quote), "{of}: no {quote:?} any more");
                questions = questions.replace(quote, " ");
            }
            let written = numbers(&questions);
            // The student's own values, as the README lists them.
            let own = |path: &str| -> Vec<f64> {
                readme
                    .lines()
                    .find_map(|l| l.strip_prefix(&format!("- `{path}` = ")))
                    .map(numbers)
                    .unwrap_or_else(|| panic!("{name} {student}: no value of {path}"))
            };
            let owns: Vec<Vec<f64>> = lesson_values.iter().map(|(p, _)| own(p)).collect();
            let in_own = |v: &[f64]| owns.iter().any(|o| o.windows(v.len()).any(|w| w == v));
            for (path, values) in &lesson_values {
                // A value the student drew too (for this path or another) may rightly be quoted.
                for v in values.iter().filter(|v| !in_own(v)) {
                    checked.push(*path);
                    let quoted = written.windows(v.len()).any(|w| w == v.as_slice());
                    assert!(
                        !quoted,
                        "{name}, {student}'s homework (their {path} = {:?}) quotes the \
                         lesson's {v:?}:\n{questions}",
                        own(path)
                    );
                }
            }
        }
        for (path, _) in &lesson_values {
            assert!(
                checked.contains(path),
                "{name}: every student drew a value the lesson writes for {path}"
            );
        }
    }
    assert!(lessons >= 3, "only {lessons} lessons vary values");
}

/// The files of the shipped lesson `lesson` copied into `dir` (made if need be).
fn copy_lesson(lesson: &str, dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    for f in std::fs::read_dir(Path::new("lessons").join(lesson)).unwrap() {
        let f = f.unwrap();
        if f.path().is_file() {
            std::fs::copy(f.path(), dir.join(f.file_name())).unwrap();
        }
    }
}

/// Lesson 02 copied into a scratch folder of lessons, its exercises.yaml with `extra` added.
fn lesson02_with(name: &str, extra: &str) -> PathBuf {
    let root = scratch(name);
    let dir = root.join("02-intersection");
    copy_lesson("02-intersection", &dir);
    let exercises = dir.join("exercises.yaml");
    let text = std::fs::read_to_string(&exercises).unwrap();
    std::fs::write(&exercises, text + extra).unwrap();
    dir
}

/// Two values that are fine on their own can clash together: a box's corners varied apart
/// (min.x in [1.5, 2.5], max.x in [2.2, 3.2]) cross where min.x > max.x, which 2.5 with the
/// others as written (max.x = 3) and 2.2 with them (min.x = 2) never show. Validation tries
/// the ends together and names exactly the two clashing combinations: min.x = 2.5 with
/// max.x = 2.2 and with its first step, 2.21.
#[test]
fn values_that_clash_only_together_are_named_together() {
    let dir = lesson02_with(
        "vary-clash",
        "vary:\n  objects.crate.box.min: [[1.5, -2, 20], [2.5, -2, 20]]\n  objects.crate.box.max: [[2.2, -1, 21], [3.2, -1, 21]]\n",
    );
    let scene = dir.join("scene.yaml");
    let text = std::fs::read_to_string(&scene).unwrap();
    // Far behind the ball, out of every exercise's way.
    let crate_box =
        "  - { name: crate, box: { min: [2, -2, 20], max: [3, -1, 21] }, material: chalk }\n";
    std::fs::write(&scene, text.trim_end().to_string() + "\n" + crate_box).unwrap();
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 2, "{report}");
    for (p, max_x) in problems.iter().zip(["2.2", "2.21"]) {
        assert!(
            p.contains("vary `objects.crate.box.max` = [")
                && p.contains(&format!("[{max_x}, -1, 21]"))
                && p.contains("`objects.crate.box.min` = [2.5, -2, 20] together")
                && p.contains("box min must be smaller than max"),
            "{report}"
        );
    }
}

/// A varied value that loads can still leave exercises without an answer: the ball moved 3
/// to the left, the ray from inside it (`inside-t`, `inside-normal`) misses it, and a student
/// who drew that value could not be graded. `lessons validate` works every exercise out at
/// each range's ends and first step and names the values (one line each, the exercises
/// listed); at x = 3 every exercise's ray still meets the ball. A `local` exercise whose ray
/// hits nothing is refused too: it has no local term.
#[test]
fn a_variation_that_leaves_exercises_without_an_answer_is_named() {
    let dir = lesson02_with(
        "vary-misses",
        "vary:\n  objects.ball.sphere.center: [[-3, 0, 0], [3, 0, 0]]\n",
    );
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 2, "{report}");
    for (p, x) in problems.iter().zip(["-3", "-2.99"]) {
        assert!(
            p.contains(&format!(
                "with vary `objects.ball.sphere.center` = [{x}, 0, 0], exercise `inside-t` (and inside-normal) cannot be worked out: the ray hits nothing"
            )),
            "{report}"
        );
    }
    let dir = lesson02_with(
        "local-misses",
        "  - id: local-miss\n    question: What is the local term of the ray straight up?\n    ask: local\n    model: blinn\n    ray: { origin: [0, 5, 0], direction: [0, 1, 0] }\n",
    );
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    let report = out(&o);
    assert!(
        report.contains("local-miss: cannot be worked out: exercise `local-miss`: the ray hits nothing, so it has no local term"),
        "{report}"
    );
}

/// A `vary:` range that reaches values the scene refuses: `max_depth` in [1, 4] in the
/// default steps of 0.01 draws fractions (1.01 is its first step), and a radius from 0 gives
/// a sphere of radius 0. `lessons validate` tries each range's ends and first step and names
/// both, and the first step of the radius, 0.01, which loads but leaves the lesson's rays
/// missing the ball; a lesson whose every student gets a refused value (`one_of: [1.5]`) hands out no
/// homework, and its rows in a class's sheet are set aside, not marked wrong or copied.
#[test]
fn a_variation_that_breaks_the_scene_is_refused_not_handed_out() {
    let dir = lesson02_with(
        "vary-breaks",
        "vary:\n  max_depth: [1, 4]\n  objects.ball.sphere.radius: [0, 2]\n",
    );
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let report = out(&o);
    let problems: Vec<&str> = report.lines().filter(|l| l.starts_with('✗')).collect();
    assert_eq!(problems.len(), 3, "{report}");
    assert!(
        problems[0].contains("vary `max_depth` = 1.01") && problems[0].contains("whole number"),
        "{report}"
    );
    assert!(
        problems[1].contains("vary `objects.ball.sphere.radius` = 0")
            && problems[1].contains("radius must be > 0"),
        "{report}"
    );
    assert!(
        problems[2].contains("with vary `objects.ball.sphere.radius` = 0.01, exercise `chord-t`")
            && problems[2].contains("the ray hits nothing"),
        "{report}"
    );

    let dir = lesson02_with(
        "vary-always-breaks",
        "vary:\n  max_depth: { one_of: [1.5] }\n",
    );
    let homework = scratch("vary-always-breaks-hw");
    let o = raytree(&[
        "homework",
        dir.to_str().unwrap(),
        "--student",
        "s1",
        "-o",
        homework.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(
        err(&o).contains("student s1's variant does not load (max_depth = 1.5)"),
        "{}",
        err(&o)
    );
    assert!(!homework.exists());
    let sheet = answer_sheet(
        "vary-always-breaks-sheet",
        "student,exercise,answer\ns1,tangent-t,3\ns2,tangent-t,4\n",
    );
    let o = raytree(&[
        "grade",
        dir.to_str().unwrap(),
        "--answers",
        sheet.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let e = out(&o) + &err(&o);
    assert!(
        e.contains("no answer graded: every row was set aside"),
        "{e}"
    );
    assert!(
        e.contains("s1, tangent-t: not graded: student s1's variant"),
        "{e}"
    );
    assert!(
        e.contains("s2, tangent-t: not graded: student s2's variant"),
        "{e}"
    );
    assert!(!out(&o).contains("answer, worked out with"), "{}", out(&o));
}

/// A question that quotes a value the lesson does not vary (a typo in `{materials.zz.kd}`)
/// would reach every student with its braces: the lesson is refused where it is read, naming
/// the exercise, the placeholder and what the lesson varies.
#[test]
fn a_question_quoting_an_unvaried_value_is_refused() {
    let dir = lesson02_with(
        "placeholder-typo",
        "vary:\n  objects.ball.sphere.radius: [1, 1.2]\n",
    );
    let exercises = dir.join("exercises.yaml");
    let text = std::fs::read_to_string(&exercises).unwrap();
    let typo = text.replacen(
        "meets the unit sphere.",
        "meets the sphere of kd {materials.zz.kd}.",
        1,
    );
    assert_ne!(typo, text);
    std::fs::write(&exercises, typo).unwrap();
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(
        out(&o).contains(
            "exercise `tangent-t`: the question quotes `{materials.zz.kd}`, which is not a value the lesson varies (it varies objects.ball.sphere.radius)"
        ),
        "{}",
        out(&o)
    );
}

/// A mistake in a lesson's exercises.yaml found after it parses is named at its line and
/// column, as a YAML mistake is: a duplicate id at the second `id`, an exercise with both a
/// pixel and a ray (the ray would be left unused) at its `ray`, a depth outside 1 to 64 (a
/// scene's own range) at its `depth`, a scene outside the lesson's folder at its `scene`
/// (`homework` writes each scene into the student's folder under that name), and a varied
/// value no scene writes at its `vary` key.
#[test]
fn a_mistake_in_exercises_yaml_is_named_at_its_line_and_column() {
    let lines = std::fs::read_to_string("lessons/02-intersection/exercises.yaml")
        .unwrap()
        .lines()
        .count();
    let exercise = |extra: &str| {
        format!("  - id: extra\n    question: Which t?\n    ask: hit_t\n    pixel: [1, 1]\n{extra}")
    };
    let cases = [
        (
            "  - id: floor-t\n    question: Again?\n    ask: hit_t\n    pixel: [1, 1]\n".to_string(),
            (1, 9),
            "duplicate exercise id `floor-t`",
        ),
        (
            exercise("    ray: { origin: [0, 0, -5], direction: [0, 0, 1] }\n"),
            (5, 10),
            "exercise `extra`: give `pixel` or `ray`, not both",
        ),
        (
            exercise("    depth: 0\n"),
            (5, 12),
            "exercise `extra`: depth 0: a depth is from 1 (the primary ray alone) to 64",
        ),
        (
            exercise("    depth: 100000\n"),
            (5, 12),
            "depth 100000",
        ),
        (
            exercise("    scene: ../shared/other.yaml\n"),
            (5, 12),
            "exercise `extra`: scene `../shared/other.yaml`: an exercise's scene is a file of the lesson's folder",
        ),
        (
            exercise("    scene: /tmp/other.yaml\n"),
            (5, 12),
            "scene `/tmp/other.yaml`",
        ),
        (
            "vary:\n  materials.nothing.kd: [0.1, 0.2]\n".to_string(),
            (2, 25),
            "vary `materials.nothing.kd`: no scene of the lesson writes that value",
        ),
    ];
    for (i, (extra, (line, column), says)) in cases.iter().enumerate() {
        let dir = lesson02_with(&format!("located-{i}"), extra);
        let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{extra}: {}{}", out(&o), err(&o));
        let at = format!(
            "{}:{}:{column}: ",
            dir.join("exercises.yaml").display(),
            lines + line
        );
        let report = out(&o);
        assert!(
            report.lines().any(|l| l.contains(&at) && l.contains(says)),
            "{extra}: want {at}…{says} in\n{report}"
        );
    }
}

/// An exercise's pixel outside its scene's image is named with the image's size and the
/// pixels it has.
#[test]
fn a_pixel_outside_the_image_is_named_with_the_images_size() {
    let dir = lesson02_with(
        "pixel-outside",
        "  - id: far\n    question: Which t?\n    ask: hit_t\n    pixel: [160, 7]\n",
    );
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(
        out(&o).contains(
            "exercise `far`: pixel 160,7 is outside its scene's 160 × 120 image (x from 0 to 159, y from 0 to 119)"
        ),
        "{}",
        out(&o)
    );
}

/// An exercise naming a light the scene does not have says so, with the lights it has.
#[test]
fn an_exercise_naming_no_light_of_the_scene_says_so() {
    let dir = lesson02_with(
        "no-such-light",
        "  - id: dark\n    question: Which s?\n    ask: shadow_factor\n    light: Lx\n    pixel: [80, 60]\n",
    );
    let o = raytree(&["lessons", "validate", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(
        out(&o).contains("exercise `dark`: the scene has no light named `Lx` (its lights: "),
        "{}",
        out(&o)
    );
}

/// A ray exercise that a student's varied scene makes impossible (a ray at height 0.9 meets a
/// ball of radius r only where r ≥ 0.9) is the lesson's fault, not the student's: their row is
/// set aside with the reason, and the exercise does not count in their total; a student whose
/// ball the ray meets is graded on it.
#[test]
fn an_exercise_a_students_values_make_impossible_is_set_aside() {
    let dir = lesson02_with(
        "impossible-for-some",
        "  - id: graze\n    question: Which t?\n    ask: hit_t\n    ray: { origin: [-5, 0.9, 0], direction: [1, 0, 0] }\n\
         vary:\n  objects.ball.sphere.radius: [0.5, 1.5]\n",
    );
    let students: Vec<String> = (1..=16).map(|k| format!("s{k}")).collect();
    let rows: String = students
        .iter()
        .map(|s| format!("{s},graze,4.56\n"))
        .collect();
    let sheet = answer_sheet("impossible-sheet", &rows);
    let v = grade_json(dir.to_str().unwrap(), &sheet);
    let problems: Vec<String> = v["problems"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["message"].as_str().unwrap().to_string())
        .collect();
    let (mut set_aside, mut graded) = (0, 0);
    for s in &students {
        let report = v["students"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["student"] == s.as_str())
            .unwrap();
        let graze = report["exercises"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["exercise"] == "graze");
        match graze {
            None => {
                set_aside += 1;
                assert_eq!(report["total"], 10, "{report}");
                assert!(
                    problems.iter().any(|p| p.starts_with(&format!(
                        "{s}, graze: not graded: with this student's values the exercise cannot be worked out"
                    ))),
                    "{problems:?}"
                );
            }
            Some(g) => {
                graded += 1;
                assert_eq!(report["total"], 11, "{report}");
                assert!(!problems.iter().any(|p| p.starts_with(&format!("{s}, "))));
                assert!(g["expected"].is_string(), "{g}");
            }
        }
    }
    assert!(
        set_aside > 0 && graded > 0,
        "{set_aside} set aside, {graded} graded"
    );
}

/// A lesson folder whose exercises file is named exercises.yml is reported among the lessons
/// that cannot be read, with what to rename, not passed over.
#[test]
fn an_exercises_file_named_yml_is_reported() {
    let dir = lesson02_with("misnamed", "");
    std::fs::rename(dir.join("exercises.yaml"), dir.join("exercises.yml")).unwrap();
    copy_lesson(
        "03-local-illumination",
        &dir.parent().unwrap().join("03-local-illumination"),
    );
    let o = raytree(&[
        "lessons",
        "validate",
        dir.parent().unwrap().to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(
        out(&o).contains(&format!(
            "{}: exercises.yml: a lesson's exercises are read from exercises.yaml (rename it)",
            dir.display()
        )),
        "{}",
        out(&o)
    );
    assert!(
        out(&o).contains("1 lesson could not be read"),
        "{}",
        out(&o)
    );
}

/// A homework folder holds the lesson's subfolders too (a texture kept in `tex/`), so its
/// scene loads and its exercise checks there; a scene that reads a file from outside the
/// lesson's folder is refused before anything is written, naming the scene and the file.
#[test]
fn homework_copies_the_lessons_subfolders_and_refuses_files_from_outside() {
    let root = scratch("homework-subfolders");
    let dir = root.join("16-textures");
    copy_lesson("16-textures", &dir);
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    std::fs::rename(dir.join("tiles.png"), dir.join("tex/tiles.png")).unwrap();
    let scene = dir.join("scene.yaml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains("image: tiles.png"));
    std::fs::write(
        &scene,
        text.replace("image: tiles.png", "image: tex/tiles.png"),
    )
    .unwrap();
    let homework = |student: &str| {
        let out = root.join(format!("hw-{student}"));
        let args = [
            "homework",
            dir.to_str().unwrap(),
            "--student",
            student,
            "-o",
        ];
        (
            raytree(&[&args[..], &[out.to_str().unwrap()]].concat()),
            out,
        )
    };
    let (o, homework_dir) = homework("s1");
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    assert_eq!(
        std::fs::read(homework_dir.join("tex/tiles.png")).unwrap(),
        std::fs::read(dir.join("tex/tiles.png")).unwrap()
    );
    let png = root.join("hw-s1.png");
    let o = raytree(&[
        "render",
        homework_dir.join("scene.yaml").to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));

    std::fs::rename(dir.join("tex/tiles.png"), root.join("tiles.png")).unwrap();
    std::fs::write(
        &scene,
        text.replace("image: tiles.png", "image: ../tiles.png"),
    )
    .unwrap();
    let (o, refused) = homework("s2");
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(
        err(&o).contains(&format!(
            "{}: reads ../tiles.png, outside the lesson's folder",
            scene.display()
        )),
        "{}",
        err(&o)
    );
    assert!(!refused.exists());
}

/// An exercise's ray direction is a direction whatever its length: (0, 1e-200, 0) and
/// (0, 1e200, 0) are lesson 03's ray straight up (which has only the ambient term left, 0.08,
/// as the lesson works it), and a direction with no number in it is refused by name.
#[test]
fn an_exercises_ray_direction_of_any_length_is_that_direction() {
    let exercises =
        std::fs::read_to_string("lessons/03-local-illumination/exercises.yaml").unwrap();
    let up = "ray: { origin: [0, -5, 0], direction: [0, 1, 0] }";
    assert!(exercises.contains(up));
    let lesson = |name: &str, direction: &str| {
        let dir = scratch(name);
        std::fs::create_dir_all(&dir).unwrap();
        for f in ["scene.yaml", "phong.yaml", "color.yaml", "README.md"] {
            std::fs::copy(
                Path::new("lessons/03-local-illumination").join(f),
                dir.join(f),
            )
            .unwrap();
        }
        let changed = format!("ray: {{ origin: [0, -5, 0], direction: {direction} }}");
        std::fs::write(
            dir.join("exercises.yaml"),
            exercises.replacen(up, &changed, 1),
        )
        .unwrap();
        dir
    };
    for (name, direction) in [
        ("tiny-dir", "[0, 1e-200, 0]"),
        ("huge-dir", "[0, 1e200, 0]"),
    ] {
        let dir = lesson(name, direction);
        let d = dir.to_str().unwrap();
        let o = raytree(&["check", d, "--exercise", "local-unlit", "--answer", "0.08"]);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{direction}: {}{}",
            out(&o),
            err(&o)
        );
    }
    let dir = lesson("nan-dir", "[0, .nan, 0]");
    let o = raytree(&[
        "check",
        dir.to_str().unwrap(),
        "--exercise",
        "local-unlit",
        "--answer",
        "0",
    ]);
    assert!(!o.status.success(), "{}", out(&o));
    assert!(
        err(&o).contains("finite, non-zero direction"),
        "{}",
        err(&o)
    );
}

/// One number given for a colour is a grey, whatever its value: right within the tolerance of
/// every channel, else wrong by the tolerance like any colour (with the hint to give r, g, b),
/// never "not the kind of answer asked" (lesson 14's edge mean is about (0.271, 0.265, 0.259)).
#[test]
fn one_number_for_a_colour_is_a_grey_colour() {
    let check = |answer: &str| {
        raytree(&[
            "check",
            "14-monte-carlo-glossy",
            "--exercise",
            "edge-mean",
            "--answer",
            answer,
        ])
    };
    let o = check("0.25");
    assert_eq!(o.status.code(), Some(0), "{}{}", out(&o), err(&o));
    let o = check("0.35");
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    let said = out(&o);
    assert!(said.contains("wrong: 0.35 is not within"), "{said}");
    assert!(said.contains("give it as r, g, b"), "{said}");
}

/// The number of numbers a hint asks for is the exercise's: t is one number (never three),
/// a direction three (never one), a colour one (grey) or three.
#[test]
fn a_hint_on_how_many_numbers_names_the_exercises_own_count() {
    let hint = |lesson: &str, exercise: &str, answer: &str| {
        let o = raytree(&["check", lesson, "--exercise", exercise, "--answer", answer]);
        assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
        out(&o)
    };
    let said = hint("02-intersection", "chord-t", "2.2,2.2");
    assert!(said.contains("t is one number, not two"), "{said}");
    let said = hint("02-intersection", "chord-t", "2.2,2.2,2.2");
    assert!(said.contains("t is one number, not a vector"), "{said}");
    let said = hint("06-refraction", "entry-direction", "0.6, -0.8");
    assert!(
        said.contains("a direction is three numbers, not two"),
        "{said}"
    );
    let said = hint("14-monte-carlo-glossy", "edge-mean", "0.25, 0.25");
    assert!(said.contains("is one number or three, not two"), "{said}");
}

/// `none` (an empty segment list, as `--help` lists it) where a t or a direction is asked is
/// a wrong answer of another kind (exit 1), as `tir` is, not text that does not read (exit 2).
#[test]
fn none_where_no_segment_list_is_asked_is_wrong() {
    for (lesson, exercise, what) in [
        ("02-intersection", "chord-t", "t is asked"),
        ("06-refraction", "entry-direction", "a direction is asked"),
    ] {
        let o = raytree(&["check", lesson, "--exercise", exercise, "--answer", "none"]);
        assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
        let said = out(&o);
        assert!(
            said.contains("none is an answer for a segment list only"),
            "{said}"
        );
        assert!(said.contains(what), "{said}");
    }
    // Where no ray is refracted, none is the right idea in the wrong words: the hint says tir.
    let o = raytree(&[
        "check",
        "06-refraction",
        "--exercise",
        "beyond-critical",
        "--answer",
        "none",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(out(&o).contains("which is answered tir"), "{}", out(&o));
}

/// "José" with é (NFC) and with e and a combining accent (NFD, as macOS and some
/// spreadsheets write it) is one student: one variant for `check` and `grade`, one row group.
#[test]
fn a_student_id_is_one_student_in_either_unicode_form() {
    let (composed, decomposed) = ("Jos\u{e9}", "Jose\u{301}");
    let expected = |student: &str| {
        let o = raytree(&[
            "check",
            "03-local-illumination",
            "--student",
            student,
            "--exercise",
            "diffuse",
            "--answer",
            "0",
            "--format",
            "json",
        ]);
        let v: serde_json::Value = serde_json::from_str(&out(&o)).unwrap();
        v["expected"].as_f64().unwrap()
    };
    let answer = expected(composed);
    assert_eq!(expected(decomposed), answer);
    let dir = scratch("unicode-ids");
    std::fs::create_dir_all(&dir).unwrap();
    let sheet = dir.join("answers.csv");
    std::fs::write(
        &sheet,
        format!("{composed},diffuse,{answer}\n{decomposed},specular-blinn,0\n"),
    )
    .unwrap();
    let report = grade_json("03-local-illumination", &sheet);
    let students = report["students"].as_array().unwrap();
    assert_eq!(students.len(), 1, "{report}");
    assert_eq!(students[0]["score"], 1, "{report}");
}

/// A sheet saved as Latin-1 (a spreadsheet's plain "CSV" on some systems) is refused with the
/// place of its first byte that is not UTF-8, counted in characters, and how to save it.
#[test]
fn an_answer_sheet_that_is_not_utf8_is_refused_at_its_line_and_column() {
    // Line 3: "Zoë M" in UTF-8 (five characters), then ü in Latin-1 (0xFC).
    let mut rows = b"s1,tangent-t,8\ns2,tangent-t,8\nZo\xc3\xab M".to_vec();
    rows.extend_from_slice(b"\xfcller,tangent-t,8\n");
    let file = answer_sheet("latin1", rows);
    let o = raytree(&[
        "grade",
        "lessons/02-intersection",
        "--answers",
        file.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(
        err(&o).contains("c.csv:3:6: not UTF-8 text: save the answers as UTF-8"),
        "{}",
        err(&o)
    );
    assert!(out(&o).is_empty(), "{}", out(&o));
}

/// `raytree homework DIR --student s1 -o OUT`, which must succeed.
fn homework_of_s1(dir: &Path, out: &Path) -> Output {
    let (dir, out) = (dir.to_str().unwrap(), out.to_str().unwrap());
    let o = raytree(&["homework", dir, "--student", "s1", "-o", out]);
    assert!(o.status.success(), "{}", err(&o));
    o
}

/// Homework written inside the lesson's own folder (`-o hw/s1` from there) leaves itself out
/// of the copy of the lesson's files: it used to copy its own temporary folder into itself
/// until the path was too long.
#[test]
fn homework_written_inside_the_lesson_leaves_itself_out() {
    let dir = scratch("hw-inside").join("03-local-illumination");
    copy_lesson("03-local-illumination", &dir);
    let out = dir.join("hw").join("s1");
    homework_of_s1(&dir, &out);
    let names = |d: &Path| -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| !n.ends_with(".svg"))
            .collect();
        names.sort();
        names
    };
    let (names, lesson) = (
        names(&out),
        names(Path::new("lessons/03-local-illumination")),
    );
    assert_eq!(
        names, lesson,
        "the homework holds the lesson's files and nothing else"
    );
}

/// Links in a lesson's folder are not followed: one to a file of the lesson is copied as that
/// file; a loop (a link to the folder itself) and a link to a file outside the lesson are
/// left out, each named on stderr.
#[cfg(unix)]
#[test]
fn homework_copies_no_link_out_of_the_lesson() {
    let root = scratch("hw-links");
    let dir = root.join("03-local-illumination");
    copy_lesson("03-local-illumination", &dir);
    let secret = root.join("secret.txt");
    std::fs::write(&secret, "not the lesson's\n").unwrap();
    std::os::unix::fs::symlink(".", dir.join("loop")).unwrap();
    std::os::unix::fs::symlink(&secret, dir.join("secret.txt")).unwrap();
    std::os::unix::fs::symlink("color.yaml", dir.join("alias.yaml")).unwrap();
    let out = root.join("hw");
    let o = homework_of_s1(&dir, &out);
    assert!(!out.join("secret.txt").exists());
    assert!(!out.join("loop").exists());
    // The link to a scene holds the student's variant of it, as the scene's own copy does.
    let alias = std::fs::read_to_string(out.join("alias.yaml")).unwrap();
    assert_eq!(
        alias,
        std::fs::read_to_string(out.join("color.yaml")).unwrap()
    );
    assert_ne!(
        alias,
        std::fs::read_to_string(dir.join("color.yaml")).unwrap(),
        "the student's values, not the lesson's"
    );
    let e = err(&o);
    assert!(
        e.contains("secret.txt: a link out of the lesson's folder"),
        "{e}"
    );
    assert!(e.contains("loop: a link to a folder"), "{e}");
}

/// A homework folder changed after `raytree homework` wrote it (the student raised kd in its
/// scene) is no longer the variant its values name: `grade` on it refuses and points to the
/// lesson, which works each student's variant out afresh; `check` on it checks the changed
/// scene, and says so. The folder as written grades as before.
#[test]
fn a_homework_folder_changed_afterwards_is_not_graded() {
    let root = scratch("hw-edited");
    let (dir, hw) = (root.join("03-local-illumination"), root.join("hw"));
    copy_lesson("03-local-illumination", &dir);
    homework_of_s1(&dir, &hw);
    let sheet = root.join("answers.csv");
    std::fs::write(&sheet, "s1,diffuse,0.1\n").unwrap();
    let grade = || {
        raytree(&[
            "grade",
            hw.to_str().unwrap(),
            "--answers",
            sheet.to_str().unwrap(),
        ])
    };
    assert_eq!(grade().status.code(), Some(0), "{}", err(&grade()));

    let scene = hw.join("scene.yaml");
    let text = std::fs::read_to_string(&scene).unwrap();
    let kd = text
        .lines()
        .find_map(|l| l.split("kd: ").nth(1))
        .and_then(|rest| rest.split([',', ' ', '}']).next())
        .expect("the scene writes kd")
        .to_string();
    std::fs::write(&scene, text.replacen(&format!("kd: {kd}"), "kd: 0.95", 1)).unwrap();
    let o = grade();
    assert_eq!(o.status.code(), Some(2), "{}{}", out(&o), err(&o));
    assert!(
        err(&o).contains("scene.yaml changed since `raytree homework` wrote it")
            && err(&o).contains("raytree grade 03-local-illumination"),
        "{}",
        err(&o)
    );
    let o = raytree(&[
        "check",
        hw.to_str().unwrap(),
        "--exercise",
        "diffuse",
        "--answer",
        "0.1",
    ]);
    assert!(
        err(&o).contains("was changed since `raytree homework` wrote it"),
        "{}",
        err(&o)
    );
}
